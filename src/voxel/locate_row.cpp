// SPDX-License-Identifier: MIT
#include "voxel/locate_row.h"

#include <cstring>

#include "common/simd.h"

namespace terrasprite {
namespace {
typedef std::int64_t v4l __attribute__((vector_size(32)));
}  // namespace

// Four pixels at a time with vector extensions (one AVX2 instruction per step
// in the AVX2 clone; no FMA there, so each product and sum rounds as in the
// scalar code and the tail below).
TS_CLONES_AVX2
void locate_slope_row(const SlopeRowLocator& L, int y, int x0, int count, double* cf, double* kf,
                      std::int32_t* key) {
  using simd::v4d;
  using simd::v4i;
  const double dy = y + 0.5 - L.vy;
  const double dy_e = dy * L.ey, dy_x = dy * L.ex;
  const double hi = double(L.key_max) + 1.0;
  int i = 0;
  for (; i + 4 <= count; i += 4) {
    const int x = x0 + i;
    const v4d dx = __builtin_convertvector((v4i){x, x + 1, x + 2, x + 3}, v4d) + 0.5 - L.vx;
    const v4d a = dx * L.ex + dy_e, b = dy_x - dx * L.ey;
    const v4d c = (b / a - L.c0) * L.inv_dc - 0.5;
    const v4d k = a * L.inv_dr;
    std::memcpy(cf + i, &c, sizeof c);
    std::memcpy(kf + i, &k, sizeof k);
    // floor(c), clamped: bounded first so the 32-bit conversion is exact.
    v4d cb = c < -2.0 ? v4d{} - 2.0 : c;
    cb = cb > hi ? v4d{} + hi : cb;
    const v4i t = __builtin_convertvector(cb, v4i);
    const v4i below =
        __builtin_convertvector(__builtin_convertvector(t, v4d) > cb, v4i);  // -1 or 0
    v4i f = t + below;
    f = f < -1 ? v4i{} - 1 : f;
    f = f > L.key_max ? v4i{} + L.key_max : f;
    std::memcpy(key + i, &f, sizeof f);
  }
  for (; i < count; ++i) {
    const double dx = (x0 + i) + 0.5 - L.vx;
    const double a = dx * L.ex + dy_e, b = dy_x - dx * L.ey;
    const double c = (b / a - L.c0) * L.inv_dc - 0.5;
    cf[i] = c;
    kf[i] = a * L.inv_dr;
    const double cb = c < -2.0 ? -2.0 : (c > hi ? hi : c);
    const std::int32_t t = std::int32_t(cb);
    const std::int32_t f = t - (double(t) > cb ? 1 : 0);
    key[i] = f < -1 ? -1 : (f > L.key_max ? L.key_max : f);
  }
}

}  // namespace terrasprite
