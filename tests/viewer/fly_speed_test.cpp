// SPDX-License-Identifier: MIT
// The viewer's default flying speed: steerable near the ground on a large
// terrain (it follows the height above ground, bounded).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include "flat_field.h"
#include "viewer/fly_controller.h"

using namespace terrasprite;
using namespace terrasprite::viewer;

namespace {

using viewer_test::flat_field;

Camera camera_at(double z) {
  Camera c;
  c.position = {0, 0, z};
  c.yaw_deg = 90;
  return c;
}

}  // namespace

TEST(FlySpeed, FollowsTheHeightAboveGroundWithinBounds) {
  EXPECT_DOUBLE_EQ(auto_speed_mps(200, 100000), 100);   // half the height per second
  EXPECT_DOUBLE_EQ(auto_speed_mps(1, 100000), 5);       // at least 5 m/s
  EXPECT_DOUBLE_EQ(auto_speed_mps(1e6, 100000), 2000);  // at most 2% of the extent
}

TEST(FlySpeed, DefaultOnA100KmTerrainNearTheGroundIsSteerable) {
  const Heightfield h = flat_field(1001, 100, 500);  // 100 km across
  FlyOptions o;
  o.clearance_m = 20;                       // the default speed; a low clearance
  FlyController fly(h, camera_at(700), o);  // 200 m above the ground
  EXPECT_NEAR(fly.speed_mps(), 100, 1e-9);  // not a tenth of the extent (10 km/s)
  InputEvent plus;
  plus.kind = InputKind::kKey;
  plus.key = GLFW_KEY_EQUAL;
  plus.action = GLFW_PRESS;
  fly.handle(plus);
  EXPECT_NEAR(fly.speed_mps(), 125, 1e-9);
  FlyOptions fixed = o;
  fixed.speed_mps = 40;
  EXPECT_DOUBLE_EQ(FlyController(h, camera_at(700), fixed).speed_mps(), 40);
}
