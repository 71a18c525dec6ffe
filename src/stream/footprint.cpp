// SPDX-License-Identifier: MIT
#include "stream/footprint.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace terrasprite {
namespace {

// A tile's world rectangle (x east, y north; row 0 is north).
struct Rect {
  double x0, x1, y0, y1;
};

Rect tile_rect(const TileSetInfo& set, int level, int tx, int ty) {
  const TerrainGrid& g = set.grid;
  const double T = double(1 << g.tile_log2) * double(1 << level);
  const double u0 = tx * T, u1 = std::min((tx + 1) * T, double(g.width - 1));
  const double v0 = ty * T, v1 = std::min((ty + 1) * T, double(g.height - 1));
  const double cx = (g.width - 1) * 0.5, cy = (g.height - 1) * 0.5;
  return {(u0 - cx) * g.spacing_x, (u1 - cx) * g.spacing_x, (cy - v1) * g.spacing_y,
          (cy - v0) * g.spacing_y};
}

double near_dist(const Rect& r, double x, double y) {
  const double dx = std::max({r.x0 - x, 0.0, x - r.x1}), dy = std::max({r.y0 - y, 0.0, y - r.y1});
  return std::hypot(dx, dy);
}

double far_dist(const Rect& r, double x, double y) {
  return std::hypot(std::max(std::abs(r.x0 - x), std::abs(r.x1 - x)),
                    std::max(std::abs(r.y0 - y), std::abs(r.y1 - y)));
}

// Smallest angle between two headings, radians.
double angle_between(double a, double b) {
  double d = std::fmod(std::abs(a - b), 2 * std::numbers::pi);
  return d > std::numbers::pi ? 2 * std::numbers::pi - d : d;
}

void footprint_at(const TileSetInfo& set, const Camera& cam, const glm::dvec3& eye,
                  const FootprintOptions& o, std::vector<TileKey>& out) {
  const TerrainGrid& g = set.grid;
  const glm::dvec3 f = cam.forward();
  const double horiz = std::hypot(f.x, f.y);
  const double heading = std::atan2(f.y, f.x);
  const double half_v = cam.fov_y_deg * std::numbers::pi / 360.0;
  const double half_h = std::atan(std::tan(half_v) * cam.aspect);
  // Looking steeply down, the view covers every heading around the eye.
  const double wedge = horiz < 0.5 ? 4.0 : std::hypot(half_h, half_v) * o.margin;
  const double cx = (g.width - 1) * 0.5, cy = (g.height - 1) * 0.5;
  for (int L = 0; L < o.levels; ++L) {
    const double hi = level_reach(set, cam, o, L) * o.margin;
    const double lo = L == 0 ? 0.0 : level_reach(set, cam, o, L) * 0.375 / o.margin;
    const double T = double(1 << g.tile_log2) * double(1 << L);
    const double up = eye.x / g.spacing_x + cx, vp = cy - eye.y / g.spacing_y;
    const double ru = hi / g.spacing_x, rv = hi / g.spacing_y;
    const int nx = set.tiles_x[std::size_t(L)], ny = set.tiles_y[std::size_t(L)];
    const int tx0 = std::max(0, int(std::floor((up - ru) / T))), tx1 = std::min(nx - 1, int(std::floor((up + ru) / T)));
    const int ty0 = std::max(0, int(std::floor((vp - rv) / T))), ty1 = std::min(ny - 1, int(std::floor((vp + rv) / T)));
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) {
        const Rect r = tile_rect(set, L, tx, ty);
        const float top = set.tile_max[std::size_t(L)][std::size_t(ty) * nx + tx];
        const double dz_near = std::max(0.0, eye.z - double(top));
        const double dn = std::hypot(near_dist(r, eye.x, eye.y), dz_near);
        const double df = std::hypot(far_dist(r, eye.x, eye.y), eye.z - double(g.min_height));
        if (dn > hi || df < lo) continue;
        const double mx = 0.5 * (r.x0 + r.x1) - eye.x, my = 0.5 * (r.y0 + r.y1) - eye.y;
        const double dc = std::hypot(mx, my);
        const double radius = 0.5 * std::hypot(r.x1 - r.x0, r.y1 - r.y0);
        if (dc > radius && wedge < std::numbers::pi &&
            angle_between(std::atan2(my, mx), heading) > wedge + std::asin(std::min(1.0, radius / dc)))
          continue;
        out.push_back({L, tx, ty, dn / std::max(hi, 1e-9)});
      }
  }
}

}  // namespace

double level_reach(const TileSetInfo& set, const Camera& camera, const FootprintOptions& o, int level) {
  const double t1 = std::min(set.grid.spacing_x, set.grid.spacing_y) /
                    std::max(camera.pixel_angle(o.image_height) * o.pixel_voxel_ratio, 1e-12);
  return t1 * double(1 << level);
}

double tile_distance(const TileSetInfo& set, int level, int tx, int ty, double x, double y) {
  return near_dist(tile_rect(set, level, tx, ty), x, y);
}

void footprint(const TileSetInfo& set, const Camera& camera, const glm::dvec3& motion,
               const FootprintOptions& o, std::vector<TileKey>& out) {
  footprint_at(set, camera, camera.position, o, out);
  if (o.lookahead_frames > 0 && (motion.x != 0 || motion.y != 0 || motion.z != 0)) {
    const std::size_t n = out.size();
    footprint_at(set, camera, camera.position + motion * o.lookahead_frames, o, out);
    for (std::size_t k = n; k < out.size(); ++k) out[k].priority += 0.5;  // after the present
  }
}

}  // namespace terrasprite
