// SPDX-License-Identifier: MIT
// Keyframe visibility (Chen et al. 1999, section 3.3): is a world point inside
// the keyframe's view and unoccluded in its depth buffer?
#include <algorithm>
#include <cmath>

#include "terrasprite/sprite/error_metric.h"

namespace terrasprite {

bool project_to_pixel(const Camera& camera, int width, int height, glm::dvec3 p,
                      glm::dvec2& pixel) {
  const glm::dvec4 clip = camera.view_projection() * glm::dvec4(p, 1.0);
  if (clip.w <= 1e-12) return false;
  pixel.x = (clip.x / clip.w * 0.5 + 0.5) * width;
  pixel.y = (0.5 - clip.y / clip.w * 0.5) * height;
  return true;
}

bool visible_in_keyframe(const Camera& key, const DepthView& d, glm::dvec3 p,
                         double rel_tolerance) {
  glm::dvec2 px;
  if (!project_to_pixel(key, d.width, d.height, p, px)) return false;
  if (!(px.x >= 0.0 && px.x <= d.width && px.y >= 0.0 && px.y <= d.height)) return false;
  const double z = glm::dot(p - key.position, key.forward());
  if (z < key.near_m || z > key.far_m) return false;
  const int ix = std::clamp(int(std::floor(px.x)), 0, d.width - 1);
  const int iy = std::clamp(int(std::floor(px.y)), 0, d.height - 1);
  // The farthest depth around the projection: a vertex on a silhouette sees
  // past it, one behind a ridge finds only the ridge's nearer depth.
  float farthest = 0.f;
  for (int y = std::max(iy - 1, 0); y <= std::min(iy + 1, d.height - 1); ++y)
    for (int x = std::max(ix - 1, 0); x <= std::min(ix + 1, d.width - 1); ++x)
      farthest = std::max(farthest, d.depth[static_cast<std::size_t>(y) * d.width + x]);
  return z <= double(farthest) * (1.0 + rel_tolerance);
}

}  // namespace terrasprite
