// SPDX-License-Identifier: MIT
// How far a path's warped frames are from their real ones (render --warp's check).
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "terrasprite/experiment/warp.h"

namespace terrasprite {

namespace {

// Distance from the eye along the view direction to the ground (the depth at
// the image centre), marched in steps of a grid spacing; the far plane when
// the view misses the ground.
double centre_depth(const Camera& c, const Heightfield& ground) {
  const double step = std::max(1.0, std::min(ground.spacing_x, ground.spacing_y));
  const glm::dvec3 dir = c.forward();
  const int steps = int(std::min(c.far_m / step, 100000.0));
  for (int i = 1; i <= steps; ++i) {
    const glm::dvec3 p = c.position + dir * (i * step);
    if (p.z <= ground.sample(p.x, p.y)) return i * step;
  }
  return c.far_m;
}

}  // namespace

WarpStride warp_stride(const std::vector<Camera>& path, int real_every, const Heightfield& ground) {
  WarpStride s;
  double worst_excess = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::size_t real = i - i % std::size_t(std::max(real_every, 1));
    if (real == i) continue;
    const Camera &from = path[real], &to = path[i];
    const double c = std::clamp(glm::dot(from.forward(), to.forward()), -1.0, 1.0);
    const double turn = glm::degrees(std::acos(c));
    // A floor of 1 m: an eye on the ground would divide by nothing.
    const double depth = std::max(1.0, centre_depth(from, ground));
    const double move = glm::length(to.position - from.position) / depth;
    s.max_turn_deg = std::max(s.max_turn_deg, turn);
    s.max_move_over_depth = std::max(s.max_move_over_depth, move);
    const double excess =
        std::max(turn / (kWarpMaxTurnOfFov * from.fov_y_deg), move / kWarpMaxMoveOverDepth);
    if (excess > worst_excess) {
      worst_excess = excess;
      s.worst_frame = int(i);
    }
  }
  s.too_far = worst_excess > 1;
  return s;
}

}  // namespace terrasprite
