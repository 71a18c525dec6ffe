// SPDX-License-Identifier: MIT
#include "sprite/keyframe_contrast.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "terrasprite/camera/frame.h"

namespace terrasprite {
namespace {

// Summed-area table with a zero first row and column: sum over [x0, x1) x [y0, y1).
struct Sat {
  int w = 0;
  std::vector<double> s;
  Sat(int width, int height) : w(width + 1), s(std::size_t(width + 1) * (height + 1), 0.0) {}
  double& at(int x, int y) { return s[std::size_t(y) * w + x]; }
  double box(int x0, int y0, int x1, int y1) const {
    auto v = [&](int x, int y) { return s[std::size_t(y) * w + x]; };
    return v(x1, y1) - v(x0, y1) - v(x1, y0) + v(x0, y0);
  }
};

}  // namespace

QuadContrast quad_contrast(const CoarseGrid& g, const Camera& key, int w, int h,
                           std::span<const std::uint8_t> rgba) {
  assert(rgba.size() >= std::size_t(w) * h * 4);
  const float sky = 0.2126f * kSkyColor[0] + 0.7152f * kSkyColor[1] + 0.0722f * kSkyColor[2];
  std::vector<float> lum(std::size_t(w) * h);
  for (std::size_t i = 0; i < lum.size(); ++i) {
    const std::uint8_t* p = &rgba[4 * i];
    // The keyframe is premultiplied over transparent sky: composite as shown.
    const float a = p[3] / 255.f;
    lum[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] + (1.f - a) * sky;
  }
  Sat grad(w, h), sum(w, h), sq(w, h);
  for (int y = 0; y < h; ++y) {
    double rg = 0, rs = 0, rq = 0;
    const int ym = std::max(y - 1, 0), yp = std::min(y + 1, h - 1);
    for (int x = 0; x < w; ++x) {
      const int xm = std::max(x - 1, 0), xp = std::min(x + 1, w - 1);
      const double l = lum[std::size_t(y) * w + x];
      const double gx =
          (lum[std::size_t(y) * w + xp] - lum[std::size_t(y) * w + xm]) / std::max(xp - xm, 1);
      const double gy =
          (lum[std::size_t(yp) * w + x] - lum[std::size_t(ym) * w + x]) / std::max(yp - ym, 1);
      rg += gx * gx + gy * gy;
      rs += l;
      rq += l * l;
      grad.at(x + 1, y + 1) = grad.at(x + 1, y) + rg;
      sum.at(x + 1, y + 1) = sum.at(x + 1, y) + rs;
      sq.at(x + 1, y + 1) = sq.at(x + 1, y) + rq;
    }
  }
  QuadContrast out;
  const std::size_t n = std::size_t(g.quad_count());
  out.gradient.assign(n, 0.f);
  out.deviation.assign(n, 0.f);
  for (int r = 0; r < g.quads_y; ++r)
    for (int c = 0; c < g.quads_x; ++c) {
      const std::size_t q = std::size_t(r) * g.quads_x + c;
      double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
      bool behind = false;
      for (const glm::dvec3& p : {g.vertex(c, r), g.vertex(c + 1, r), g.vertex(c, r + 1),
                                  g.vertex(c + 1, r + 1), g.centre[q]}) {
        glm::dvec2 px;
        if (!project_to_pixel(key, w, h, p, px)) {
          behind = true;
          break;
        }
        x0 = std::min(x0, px.x);
        y0 = std::min(y0, px.y);
        x1 = std::max(x1, px.x);
        y1 = std::max(y1, px.y);
      }
      if (behind) continue;
      const int ix0 = int(std::clamp(std::floor(x0), 0.0, double(w)));
      const int iy0 = int(std::clamp(std::floor(y0), 0.0, double(h)));
      const int ix1 = int(std::clamp(std::ceil(x1), 0.0, double(w)));
      const int iy1 = int(std::clamp(std::ceil(y1), 0.0, double(h)));
      if (ix1 <= ix0 || iy1 <= iy0) continue;
      const double area = double(ix1 - ix0) * (iy1 - iy0);
      const double m = sum.box(ix0, iy0, ix1, iy1) / area;
      out.gradient[q] = float(std::sqrt(grad.box(ix0, iy0, ix1, iy1) / area));
      out.deviation[q] = float(std::sqrt(std::max(sq.box(ix0, iy0, ix1, iy1) / area - m * m, 0.0)));
    }
  return out;
}

}  // namespace terrasprite
