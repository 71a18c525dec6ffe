// SPDX-License-Identifier: MIT
// Viewpoint prediction for asynchronous keyframes: linear extrapolation of
// position and angles, yaw wrapped through north.
#include "sprite/camera_prediction.h"

#include <gtest/gtest.h>

#include "terrasprite/terrain/synth.h"

namespace terrasprite {
namespace {

TEST(CameraPredictor, ExtrapolatesPositionAndWrapsYaw) {
  const Heightfield h = synthesize_terrain({.size = 33, .spacing_m = 30.0, .relief_m = 100.0});
  CameraPredictor p(3);
  Camera c;
  c.position = {0, 0, 500};
  c.pitch_deg = -30;
  p.observe(c);
  EXPECT_EQ(p.predict(5, h).position, c.position);  // one camera: no motion known
  for (int i = 1; i <= 3; ++i) {                    // 10 m east and 10 degrees clockwise per frame
    c.position.x += 10;
    c.yaw_deg = i == 1 ? 350 : i == 2 ? 0 : 10;
    p.observe(c);
  }
  const Camera ahead = p.predict(4, h);
  EXPECT_NEAR(ahead.position.x, c.position.x + 40, 1e-9);
  EXPECT_NEAR(ahead.position.y, 0, 1e-9);
  EXPECT_NEAR(ahead.yaw_deg, 50, 1e-9);  // 10 + 4 x 10, not 10 - 4 x 170
  EXPECT_NEAR(ahead.pitch_deg, -30, 1e-9);
  EXPECT_GT(ahead.far_m, ahead.near_m);
  p.clear();
  p.observe(c);
  EXPECT_EQ(p.predict(4, h).position, c.position);
}

}  // namespace
}  // namespace terrasprite
