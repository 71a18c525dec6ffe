// SPDX-License-Identifier: MIT
#include "voxel/locate_row.h"

#include <cstring>

#include "common/simd.h"

namespace terrasprite {
// Four pixels at a time with vector extensions (one AVX2 instruction per step
// in the AVX2 clone; no FMA there, so each product and sum rounds as in the
// scalar code and the tail below).
TS_CLONES_AVX2
void locate_slope_row(const SlopeRowLocator& L, int y, int x0, int count, double* cf, double* kf) {
  using simd::v4d;
  using simd::v4i;
  const double dy = y + 0.5 - L.vy;
  const double dy_e = dy * L.ey, dy_x = dy * L.ex;
  int i = 0;
  for (; i + 4 <= count; i += 4) {
    const int x = x0 + i;
    const v4d dx = __builtin_convertvector((v4i){x, x + 1, x + 2, x + 3}, v4d) + 0.5 - L.vx;
    const v4d a = dx * L.ex + dy_e, b = dy_x - dx * L.ey;
    const v4d c = (b / a - L.c0) * L.inv_dc - 0.5;
    const v4d k = a * L.inv_dr;
    std::memcpy(cf + i, &c, sizeof c);
    std::memcpy(kf + i, &k, sizeof k);
  }
  for (; i < count; ++i) {
    const double dx = (x0 + i) + 0.5 - L.vx;
    const double a = dx * L.ex + dy_e, b = dy_x - dx * L.ey;
    cf[i] = (b / a - L.c0) * L.inv_dc - 0.5;
    kf[i] = a * L.inv_dr;
  }
}

namespace {
// atan2(b, a) of four lanes: atan of min/max over [0, 1] (Cephes atan.c: the
// argument above 0.66 reduced by pi/4, then x + x z P(z)/Q(z), z = x^2), then
// the octant.
[[gnu::always_inline]] inline void atan2_v4(const simd::v4d& b, const simd::v4d& a,
                                            simd::v4d& out) {
  using simd::v4d;
  constexpr double kPi = 3.14159265358979323846, kMoreBits = 6.123233995736765886130e-17;
  const v4d zero{}, one = zero + 1.0;
  const v4d ab = a < 0 ? -a : a, bb = b < 0 ? -b : b;
  const v4d mx = ab > bb ? ab : bb, mn = ab > bb ? bb : ab;
  const v4d t = mn / (mx > 0 ? mx : one);
  const auto big = t > 0.66;
  const v4d x = big ? (t - 1.0) / (t + 1.0) : t;
  const v4d z = x * x;
  const v4d p = (((-8.750608600031904122785e-1 * z - 1.615753718733365076637e1) * z -
                  7.500855792314704667340e1) *
                     z -
                 1.228866684490136173410e2) *
                    z -
                6.485021904942025371773e1;
  const v4d q = ((((z + 2.485846490142306297962e1) * z + 1.650270098316988542046e2) * z +
                  4.328810604912902668951e2) *
                     z +
                 4.853903996359136964868e2) *
                    z +
                1.945506571482613964425e2;
  v4d r = x * (z * p / q) + x;
  r = big ? (kPi / 4) + (r + 0.5 * kMoreBits) : r;
  r = bb > ab ? kPi / 2 - r : r;
  r = a < 0 ? kPi - r : r;
  out = b < 0 ? -r : r;
}
}  // namespace

TS_CLONES_AVX2
void locate_polar_row(const PolarRowLocator& L, int y, int x0, int count, double* cf, double* kf) {
  using simd::v4d;
  using simd::v4i;
  constexpr double kTwoPi = 2 * 3.14159265358979323846;
  const double dy = y + 0.5 - L.vy;
  const double dy_e = dy * L.ey, dy_x = dy * L.ex;
  // Pixels x .. x + 3 into c (columns) and k (samples).
  auto four = [&](int x, v4d& c, v4d& k) {
    const v4d dx = __builtin_convertvector((v4i){x, x + 1, x + 2, x + 3}, v4d) + 0.5 - L.vx;
    const v4d a = dx * L.ex + dy_e, b = dy_x - dx * L.ey;
    v4d ang;
    atan2_v4(b, a, ang);
    if (L.wrap) ang = ang < 0 ? ang + kTwoPi : ang;
    c = (ang - L.c0) * L.inv_dc - 0.5;
    const v4d r2 = dx * dx + dy * dy;
    for (int l = 0; l < 4; ++l) k[l] = __builtin_sqrt(r2[l]);
    k *= L.inv_dr;
  };
  int i = 0;
  v4d c, k;
  for (; i + 4 <= count; i += 4) {
    four(x0 + i, c, k);
    std::memcpy(cf + i, &c, sizeof c);
    std::memcpy(kf + i, &k, sizeof k);
  }
  if (i < count) {
    four(x0 + i, c, k);
    for (int l = 0; i + l < count; ++l) {
      cf[i + l] = c[l];
      kf[i + l] = k[l];
    }
  }
}

}  // namespace terrasprite
