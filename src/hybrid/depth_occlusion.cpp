// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/depth_occlusion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "hybrid/sphere_tangents.h"

namespace terrasprite {

SphereOnScreen sphere_on_screen(const Camera& camera, int width, int height, glm::dvec3 centre_m,
                                double radius_m) {
  SphereOnScreen s;
  const glm::dvec3 to = centre_m - camera.position;
  const double z = glm::dot(to, camera.forward());
  s.nearest_depth_m = z - radius_m;
  s.straddles_near = !(s.nearest_depth_m > camera.near_m);
  if (s.straddles_near) return s;  // also z <= r: the tangent planes are not both in front
  const double ty = std::tan(glm::radians(camera.fov_y_deg) / 2), tx = ty * camera.aspect;
  const auto [xl, xh] = tangent_slopes(glm::dot(to, camera.right()), z, radius_m);
  const auto [yl, yh] = tangent_slopes(glm::dot(to, camera.up()), z, radius_m);
  // Window pixel p covers [p, p + 1) of x = (slope / tx + 1) / 2 * width; a
  // pixel more each side absorbs rounding and the rasteriser's edge rules.
  // Clamped before the conversion: a sphere just past the near plane has
  // slopes far outside any int.
  auto pixel = [](double slope, double t, int n) {
    return int(std::floor(std::clamp((slope / t + 1) / 2 * n, -2.0, n + 2.0)));
  };
  auto lo = [&](double slope, double t, int n) { return pixel(slope, t, n) - 1; };
  auto hi = [&](double slope, double t, int n) { return pixel(slope, t, n) + 1; };
  s.rect.x0 = std::max(0, lo(xl, tx, width));
  s.rect.x1 = std::min(width - 1, hi(xh, tx, width));
  s.rect.y0 = std::max(0, lo(yl, ty, height));
  s.rect.y1 = std::min(height - 1, hi(yh, ty, height));
  return s;
}

DepthOcclusion::DepthOcclusion(const std::vector<float>& raw, int width, int height,
                               const Camera& camera)
    : width_(width), height_(height), near_m_(camera.near_m), far_m_(camera.far_m) {
  if (width <= 0 || height <= 0 || raw.size() != std::size_t(width) * std::size_t(height))
    throw std::invalid_argument("DepthOcclusion: depth buffer size does not match the image");
  levels_.push_back({width, height, raw});
  while (levels_.back().w > 1 || levels_.back().h > 1) {
    const Level& f = levels_.back();
    Level c{(f.w + 1) / 2, (f.h + 1) / 2, {}};
    c.min_depth.resize(std::size_t(c.w) * c.h);
    for (int y = 0; y < c.h; ++y)
      for (int x = 0; x < c.w; ++x) {
        const int x0 = 2 * x, y0 = 2 * y;
        const int x1 = std::min(x0 + 1, f.w - 1), y1 = std::min(y0 + 1, f.h - 1);
        auto at = [&](int px, int py) { return f.min_depth[std::size_t(py) * f.w + px]; };
        c.min_depth[std::size_t(y) * c.w + x] =
            std::min(std::min(at(x0, y0), at(x1, y0)), std::min(at(x0, y1), at(x1, y1)));
      }
    levels_.push_back(std::move(c));
  }
}

bool DepthOcclusion::nearer(int level, int tx, int ty, const PixelRect& r, float threshold) const {
  const Level& l = levels_[std::size_t(level)];
  if (l.min_depth[std::size_t(ty) * l.w + tx] > threshold)
    return true;  // the whole block is nearer
  if (level == 0) return false;
  // Some pixel of the block is not nearer: look at the children inside `r`.
  const Level& f = levels_[std::size_t(level - 1)];
  for (int cy = 2 * ty; cy <= std::min(2 * ty + 1, f.h - 1); ++cy)
    for (int cx = 2 * tx; cx <= std::min(2 * tx + 1, f.w - 1); ++cx) {
      const int s = level - 1;
      if ((cx + 1) << s <= r.x0 || cx << s > r.x1 || (cy + 1) << s <= r.y0 || cy << s > r.y1)
        continue;
      if (!nearer(s, cx, cy, r, threshold)) return false;
    }
  return true;
}

bool DepthOcclusion::hidden(const SphereOnScreen& s) const {
  if (levels_.empty() || s.straddles_near || s.rect.empty()) return false;
  const PixelRect& r = s.rect;
  if (r.x0 < 0 || r.y0 < 0 || r.x1 >= width_ || r.y1 >= height_) return false;
  // The reversed-Z depth of the sphere's nearest point (gl::projection_reversed_z):
  // a pixel occludes it when its stored depth is larger (nearer).
  const double z = s.nearest_depth_m;
  // Rounded up to the next float, so rounding never makes a pixel nearer.
  const float threshold = std::nextafter(float(near_m_ * (far_m_ - z) / (z * (far_m_ - near_m_))),
                                         std::numeric_limits<float>::infinity());
  // Start where the rectangle spans at most 2 x 2 texels.
  int level = 0;
  while (level + 1 < int(levels_.size()) &&
         ((r.x1 >> level) - (r.x0 >> level) > 1 || (r.y1 >> level) - (r.y0 >> level) > 1))
    ++level;
  for (int ty = r.y0 >> level; ty <= r.y1 >> level; ++ty)
    for (int tx = r.x0 >> level; tx <= r.x1 >> level; ++tx)
      if (!nearer(level, tx, ty, r, threshold)) return false;
  return true;
}

}  // namespace terrasprite
