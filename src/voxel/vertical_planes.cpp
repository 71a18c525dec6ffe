// SPDX-License-Identifier: MIT
// Vertical planes through the eye in the image (Cohen-Or et al. cast rays in
// vertical planes; with pitch and roll those planes are the lines through the
// vertical vanishing point, and looking straight down they are radial).
//
//        V (far below: nearly parallel lines)     V inside the image: polar
//   +-----------------+                        +-----------------+
//   | \   |   |   /   |                        |  \   |   /      |
//   |  \  |   |  /    |                        | --- V ----      |
//   |   \ |   | /     |                        |  /   |   \      |
//   +-----------------+                        +-----------------+
#include "voxel/vertical_planes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace terrasprite {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kMargin = 2.0;  // pixels around the image the columns cover
constexpr int kMaxStride = 32;   // coarsest tier of the polar layout: every 32nd column
constexpr int kMinCoarse = 64;   // ... keeping at least this many columns
}  // namespace

void PlaneLayout::direction(double p, double& wx, double& wy) const {
  const double px = -ey, py = ex;  // perpendicular to e
  if (polar) {
    wx = std::cos(p) * ex + std::sin(p) * px;
    wy = std::cos(p) * ey + std::sin(p) * py;
  } else {
    wx = ex + p * px;
    wy = ey + p * py;
  }
}

void PlaneLayout::locate(double x, double y, double& cf, double& kf) const {
  const double dx = x - vx, dy = y - vy;
  const double a = dx * ex + dy * ey, b = dx * -ey + dy * ex;
  if (polar) {
    double ang = std::atan2(b, a);
    if (wrap && ang < 0) ang += 2 * kPi;
    cf = (ang - c0) / dc - 0.5;
    kf = std::sqrt(dx * dx + dy * dy) / dr;
  } else {
    cf = (b / a - c0) / dc - 0.5;
    kf = a / dr;
  }
}

std::int64_t PlaneLayout::tier_start(int c) const {
  if (smax == 1 || c == 0) return 0;
  const int low = c & -c;  // largest power of 2 dividing c
  if (low >= smax) return 0;
  // Pixels read column c only at strides s <= low, i.e. where kf dc > kTierSpacing / (2 low).
  return std::max<std::int64_t>(0, std::int64_t(std::floor(kTierSpacing / (2.0 * low * dc))) - 2);
}

bool PlaneLayout::rows(int c, int width, int height, std::int64_t& k0, std::int64_t& k1) const {
  double wx, wy;
  column_dir(c, wx, wy);
  // Clip V + s (wx, wy), s >= 0, to the image rectangle with its margin.
  double s0 = 0, s1 = std::numeric_limits<double>::infinity();
  auto slab = [&](double o, double w, double lo, double hi) {
    if (std::abs(w) < 1e-300) return o >= lo && o <= hi;
    double a = (lo - o) / w, b = (hi - o) / w;
    s0 = std::max(s0, std::min(a, b));
    s1 = std::min(s1, std::max(a, b));
    return true;
  };
  if (!slab(vx, wx, -kMargin, width + kMargin) || !slab(vy, wy, -kMargin, height + kMargin) ||
      !(s1 >= s0))
    return false;
  k0 = std::max<std::int64_t>(0, std::int64_t(std::floor(s0 / dr)) - 1);
  k1 = std::int64_t(std::ceil(s1 / dr)) + 1;
  return true;
}

PlaneLayout make_plane_layout(const Camera& cam, int width, int height, double oversample) {
  PlaneLayout L;
  oversample = std::max(oversample, 0.25);
  L.dr = 1.0 / oversample;
  const double t = std::tan(cam.fov_y_deg * kPi / 360.0);
  const double fx = width / (2.0 * t * cam.aspect), fy = height / (2.0 * t);
  const glm::dvec3 f = cam.forward(), r = cam.right(), u = cam.up();
  // Nadir (0, 0, -1) in camera coordinates; its image is V (so is the zenith's).
  const double cx = -r.z, cy = -u.z, cz = -f.z;
  const double ox = fx * cx, oy = -fy * cy;  // (V - centre) * cz
  const double mx = width * 0.5, my = height * 0.5;
  const double far = 1e4 * std::max(width, height);
  const double olen = std::hypot(ox, oy);
  if (olen >= far * std::abs(cz)) {
    // Level camera: V at "infinity" below; place it far along the nadir's direction.
    L.vx = mx + ox / olen * far;
    L.vy = my + oy / olen * far;
    L.rise_outward = true;
  } else {
    L.vx = mx + ox / cz;
    L.vy = my + oy / cz;
    L.rise_outward = cz > 0;
  }
  const double half_diag = 0.5 * std::hypot(width, height);
  const double dv = std::hypot(mx - L.vx, my - L.vy);
  L.polar = dv < 1.5 * half_diag;
  L.wrap = L.vx > -kMargin && L.vx < width + kMargin && L.vy > -kMargin && L.vy < height + kMargin;
  if (dv > 1e-9) {
    L.ex = (mx - L.vx) / dv;
    L.ey = (my - L.vy) / dv;
  } else {
    L.ex = 0;
    L.ey = 1;
  }
  const double corners[4][2] = {{-kMargin, -kMargin},
                                {width + kMargin, -kMargin},
                                {-kMargin, height + kMargin},
                                {width + kMargin, height + kMargin}};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, reach = 0;
  for (const auto& c : corners) {
    const double dx = c[0] - L.vx, dy = c[1] - L.vy;
    const double a = dx * L.ex + dy * L.ey, b = dx * -L.ey + dy * L.ex;
    const double p = L.polar ? std::atan2(b, a) : b / a;
    lo = std::min(lo, p);
    hi = std::max(hi, p);
    reach = std::max(reach, L.polar ? std::hypot(dx, dy) : a);
  }
  if (L.wrap) {
    lo = 0;
    hi = 2 * kPi;
  }
  // Adjacent columns are at most 1/oversample pixels apart at the far end.
  const double span = std::max(hi - lo, 1e-12);
  L.columns =
      std::clamp(int(std::ceil(span * reach * oversample)) + 1, 1, 64 * std::max(width, height));
  if (L.polar) {
    // Tiers: the smallest radius in the image (0 when V is inside) sets the
    // coarsest stride; columns are rounded up so the coarse ones close the
    // circle (wrap: n a multiple of smax) or end on the last column (n - 1).
    double near = 0;
    if (!L.wrap) {
      const double cx = std::clamp(L.vx, -kMargin, width + kMargin);
      const double cy = std::clamp(L.vy, -kMargin, height + kMargin);
      near = std::hypot(cx - L.vx, cy - L.vy);
    }
    const double dc_fine = span / L.columns;
    const double t = near * oversample * dc_fine / PlaneLayout::kTierSpacing;
    int smax = 1;
    while (smax < kMaxStride && t * (2 * smax) <= 1.0 && L.columns / (2 * smax) >= kMinCoarse)
      smax *= 2;
    L.smax = smax;
    if (L.wrap)
      L.columns = (L.columns + smax - 1) / smax * smax;
    else
      L.columns = (L.columns - 1 + smax - 1) / smax * smax + 1;
  }
  L.c0 = lo;
  L.dc = span / L.columns;
  return L;
}

}  // namespace terrasprite
