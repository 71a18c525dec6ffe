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
  const double sx = 2.0 / out.w, sy = 2.0 / out.h;
  Frame& f = result.frame;
  tbb::parallel_for(tbb::blocked_range<int>(0, out.h, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      const double ny = (y + 0.5) * sy - 1.0;
      // Along a row the polynomial is quadratic in x: a + b x + c x^2.
      const double ax = cx[0] + cx[2] * ny + cx[5] * ny * ny, bx = cx[1] + cx[4] * ny, qx = cx[3];
      const double ay = cy[0] + cy[2] * ny + cy[5] * ny * ny, by = cy[1] + cy[4] * ny, qy = cy[3];
      std::uint8_t* px = f.color.px(0, y);
      float* depth = f.depth.data() + std::size_t(y) * out.w;
      std::uint8_t* hole = result.holes.data() + std::size_t(y) * out.w;
      for (int x = 0; x < out.w; ++x, px += 4) {
        const double nx = (x + 0.5) * sx - 1.0;
        const double rx = ax + (bx + qx * nx) * nx, ry = ay + (by + qy * nx) * nx;
        const std::uint32_t c = Reference::bilinear_packed(ref.frame.color, float(rx), float(ry));
        std::memcpy(px, &c, 4);
        depth[x] = ref.depth_nearest(rx, ry);
        hole[x] = !ref.inside(rx, ry);
        if (options.keep_sources) {
          const std::size_t i = std::size_t(y) * out.w + x;
          result.source_x[i] = hole[x] ? std::numeric_limits<float>::quiet_NaN() : float(rx);
          result.source_y[i] = hole[x] ? std::numeric_limits<float>::quiet_NaN() : float(ry);
        }
      }
    }
  });
}

}  // namespace terrasprite::warp
