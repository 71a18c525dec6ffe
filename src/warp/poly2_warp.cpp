// SPDX-License-Identifier: MIT
// The paper's post-render warp (Cohen-Or, Rich, Lerner, Shenkar, "A real-time
// photo-realistic visual flythrough", section on image warping): nine control
// points spread evenly over the output image, each the 3D point the real frame
// sees there, projected into the new camera; a pair of second-degree
// polynomials (12 coefficients) mapping new pixel -> real-frame pixel, fitted
// by least squares and applied with bilinear sampling.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "common/simd.h"
#include "warp/bilinear.h"
#include "warp/warp_internal.h"

namespace terrasprite::warp {
namespace {

// Monomials 1, x, y, x^2, xy, y^2 of normalised coordinates.
constexpr int kTerms = 6;
using Coeffs = std::array<double, kTerms>;

void monomials(double x, double y, double m[kTerms]) {
  m[0] = 1;
  m[1] = x;
  m[2] = y;
  m[3] = x * x;
  m[4] = x * y;
  m[5] = y * y;
}

// Solves the n x n system a x = b (row-major, n <= 6) by Gaussian elimination
// with partial pivoting; false when singular.
bool solve(double a[kTerms][kTerms], double b[kTerms], int n) {
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
    if (std::abs(a[p][c]) < 1e-12) return false;
    std::swap(a[p], a[c]);
    std::swap(b[p], b[c]);
    for (int r = c + 1; r < n; ++r) {
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < n; ++k) a[r][k] -= f * a[c][k];
      b[r] -= f * b[c];
    }
  }
  for (int c = n - 1; c >= 0; --c) {
    for (int k = c + 1; k < n; ++k) b[c] -= a[c][k] * b[k];
    b[c] /= a[c][c];
  }
  return true;
}

struct ControlPoint {
  double nx, ny;  // new-camera pixel, normalised
  double rx, ry;  // real-frame pixel
};

// Least squares over the points with the first n monomials (6: quadratic,
// 3: affine when too few points survive); unused coefficients stay 0.
bool fit(const std::vector<ControlPoint>& pts, int n, Coeffs& cx, Coeffs& cy) {
  double ata[kTerms][kTerms] = {}, bx[kTerms] = {}, by[kTerms] = {};
  for (const ControlPoint& p : pts) {
    double m[kTerms];
    monomials(p.nx, p.ny, m);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) ata[i][j] += m[i] * m[j];
      bx[i] += m[i] * p.rx;
      by[i] += m[i] * p.ry;
    }
  }
  double ata2[kTerms][kTerms];
  std::copy(&ata[0][0], &ata[0][0] + kTerms * kTerms, &ata2[0][0]);
  if (!solve(ata, bx, n) || !solve(ata2, by, n)) return false;
  cx.fill(0);
  cy.fill(0);
  for (int i = 0; i < n; ++i) {
    cx[i] = bx[i];
    cy[i] = by[i];
  }
  return true;
}

// The nine control points: an even 3 x 3 grid over the output image, seen in
// the real frame (same pixel offset from the image centre, scaled by the
// ratio of focal lengths), lifted to 3D with the real frame's depth.
std::vector<ControlPoint> control_points(const Reference& ref, const Pinhole& out) {
  std::vector<ControlPoint> pts;
  const double sx = 2.0 / out.w, sy = 2.0 / out.h;
  for (int b = 0; b < 3; ++b)
    for (int a = 0; a < 3; ++a) {
      const double ox = out.w * (0.05 + 0.45 * a), oy = out.h * (0.05 + 0.45 * b);
      const double rx = ref.cam.mx + (ox - out.mx) * ref.cam.fx / out.fx;
      const double ry = ref.cam.my + (oy - out.my) * ref.cam.fy / out.fy;
      const float z = ref.depth_nearest(rx, ry);
      double nx, ny, depth;
      const bool seen = z < Frame::kSky ? out.project(ref.cam.unproject(rx, ry, z), nx, ny, depth)
                                        : out.project_dir(ref.cam.ray(rx, ry), nx, ny);
      if (seen) pts.push_back({nx * sx - 1.0, ny * sy - 1.0, rx, ry});
    }
  return pts;
}

// One output row's mapping in pixel units: rx = ax + x (bx + x cx) at pixel
// x (x counted from 0; the centre offset folded in), likewise ry; float
// keeps it well under 1e-3 px for images up to 16384 wide.
struct RowMap {
  float ax, bx, cx, ay, by, cy;
};

RowMap row_map(const Coeffs& cx, const Coeffs& cy, const Pinhole& out, int y) {
  const double sx = 2.0 / out.w, sy = 2.0 / out.h, c0 = 0.5 * sx - 1.0;
  const double ny = (y + 0.5) * sy - 1.0;
  // Along a row the polynomial is quadratic in nx = sx x + c0: a + b nx + q nx^2.
  auto fold = [&](const Coeffs& c, float& a0, float& a1, float& a2) {
    const double a = c[0] + c[2] * ny + c[5] * ny * ny, b = c[1] + c[4] * ny, q = c[3];
    a0 = float(a + b * c0 + q * c0 * c0);
    a1 = float(b * sx + 2.0 * q * sx * c0);
    a2 = float(q * sx * sx);
  };
  RowMap m;
  fold(cx, m.ax, m.bx, m.cx);
  fold(cy, m.ay, m.by, m.cy);
  return m;
}

// Pixels [x0, x1) of one row (x1 - x0 <= kSpan): bilinear colour (8-bit
// weights, exact at pixel centres), nearest depth and the outside-the-image
// mask. The coordinates and clamps come first, in a loop without branches
// that vectorises, into the caller's `taps`; then the 2 x 2 reads, blended
// across vector lanes. The reference is at least 2 x 2 pixels.
constexpr int kSpan = 128;

struct SpanTaps {
  int off[kSpan], near[kSpan];  // bilinear block; nearest texel
  std::uint32_t wx[kSpan], wy[kSpan];
};

TS_CLONES_AVX2
void poly2_span(const RowMap& m, int x0, int x1, const std::uint32_t* __restrict src,
                const float* __restrict src_depth, int sw, int sh, std::uint32_t* __restrict color,
                float* __restrict depth, std::uint8_t* __restrict hole, SpanTaps& taps) {
  const float fw = float(sw), fh = float(sh);
  int* __restrict off = taps.off;
  int* __restrict near = taps.near;
  std::uint32_t* __restrict wx = taps.wx;
  std::uint32_t* __restrict wy = taps.wy;
  const int n = x1 - x0;
  for (int k = 0; k < n; ++k) {
    const float fx = float(x0 + k);
    const float rx = m.ax + fx * (m.bx + fx * m.cx), ry = m.ay + fx * (m.by + fx * m.cy);
    hole[x0 + k] = std::uint8_t((rx < 0.f) | (ry < 0.f) | (rx > fw) | (ry > fh));
    tap(rx, ry, sw, sh, off[k], wx[k], wy[k]);
    const int ni = std::min(std::max(int(rx), 0), sw - 1);
    const int nj = std::min(std::max(int(ry), 0), sh - 1);
    near[k] = nj * sw + ni;
  }
  bilinear_span(src, sw, off, wx, wy, n, color + x0);
  for (int k = 0; k < n; ++k) depth[x0 + k] = src_depth[near[k]];
}

}  // namespace

void warp_poly2(const Reference& ref, const Pinhole& out, const WarpOptions& options,
                WarpedFrame& result) {
  const std::vector<ControlPoint> pts = control_points(ref, out);
  Coeffs cx{}, cy{};
  // Quadratic with enough points; else affine; else the identity view.
  if (!(pts.size() >= 6 && fit(pts, 6, cx, cy)) && !(pts.size() >= 3 && fit(pts, 3, cx, cy))) {
    cx = {ref.cam.mx, ref.cam.fx / out.fx * out.mx, 0, 0, 0, 0};
    cy = {ref.cam.my, 0, ref.cam.fy / out.fy * out.my, 0, 0, 0};
  }
  Frame& f = result.frame;
  const int sw = ref.cam.w, sh = ref.cam.h;
  const bool tiny = sw < 2 || sh < 2;  // the span kernel reads a 2 x 2 block
  const auto* src = reinterpret_cast<const std::uint32_t*>(ref.frame.color.rgba.data());
  tbb::parallel_for(
      tbb::blocked_range<int>(0, out.h, 16), [&](const tbb::blocked_range<int>& rows) {
        SpanTaps taps;
        for (int y = rows.begin(); y < rows.end(); ++y) {
          const RowMap m = row_map(cx, cy, out, y);
          auto* color = reinterpret_cast<std::uint32_t*>(f.color.px(0, y));
          float* depth = f.depth.data() + std::size_t(y) * out.w;
          std::uint8_t* hole = result.holes.data() + std::size_t(y) * out.w;
          if (!tiny) {
            for (int x = 0; x < out.w; x += kSpan)
              poly2_span(m, x, std::min(x + kSpan, out.w), src, ref.frame.depth.data(), sw, sh,
                         color, depth, hole, taps);
          }
          if (!tiny && !options.keep_sources) continue;
          for (int x = 0; x < out.w; ++x) {
            const float fx = float(x);
            const float rx = m.ax + fx * (m.bx + fx * m.cx), ry = m.ay + fx * (m.by + fx * m.cy);
            if (tiny) {
              color[x] = Reference::bilinear_packed(ref.frame.color, rx, ry);
              depth[x] = ref.depth_nearest(rx, ry);
              hole[x] = !ref.inside(rx, ry);
            }
            if (options.keep_sources) {
              const std::size_t i = std::size_t(y) * out.w + x;
              result.source_x[i] = hole[x] ? std::numeric_limits<float>::quiet_NaN() : rx;
              result.source_y[i] = hole[x] ? std::numeric_limits<float>::quiet_NaN() : ry;
            }
          }
        }
      });
}

}  // namespace terrasprite::warp
