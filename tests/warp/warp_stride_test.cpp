// SPDX-License-Identifier: MIT
// render --warp's check of how far warped frames are from their real ones.
// No rendering; well under a second.
#include <gtest/gtest.h>

#include "terrasprite/experiment/warp.h"

namespace terrasprite {
namespace {

Heightfield flat_ground() {
  Heightfield h;
  h.width = h.height = 201;
  h.spacing_x = h.spacing_y = 10;
  h.heights.assign(std::size_t(h.width) * h.height, 0.f);
  return h;
}

// `n` cameras 100 m above flat ground looking 45 degrees down (the ground
// about 141 m ahead), each `step_m` further east and `turn_deg` further round
// than the last.
std::vector<Camera> path(int n, double step_m, double turn_deg) {
  std::vector<Camera> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    v[std::size_t(i)].position = {i * step_m, 0, 100};
    v[std::size_t(i)].yaw_deg = i * turn_deg;
    v[std::size_t(i)].pitch_deg = -45;
  }
  return v;
}

TEST(WarpStride, SmallStepsWarpAndLargeOnesAreTooFar) {
  const Heightfield g = flat_ground();
  const WarpStride near = warp_stride(path(12, 1, 0.5), 4, g);
  EXPECT_FALSE(near.too_far);
  // 3 m from the real frame over the ground 141 m ahead (marched in 10 m steps).
  EXPECT_GT(near.max_move_over_depth, 3.0 / 160);
  EXPECT_LT(near.max_move_over_depth, 3.0 / 140);
  const WarpStride turning = warp_stride(path(12, 1, 20), 4, g);
  EXPECT_TRUE(turning.too_far);
  EXPECT_NEAR(turning.max_turn_deg, 41.41, 0.01);  // 60 deg of yaw 45 deg down
  const WarpStride moving = warp_stride(path(12, 20, 0), 4, g);
  EXPECT_TRUE(moving.too_far);
  EXPECT_EQ(moving.worst_frame, 3);
  EXPECT_FALSE(warp_stride(path(12, 50, 20), 1, g).too_far);  // every frame real
}

}  // namespace
}  // namespace terrasprite
