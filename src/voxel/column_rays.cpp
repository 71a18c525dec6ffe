// SPDX-License-Identifier: MIT
#include "voxel/column_rays.h"

#include <cmath>
#include <cstring>

#include "common/simd.h"

namespace terrasprite {

TS_CLONES_AVX2
void column_rays(const double d0[3], const double dk[3], std::int64_t k_first, int step,
                 std::int64_t count, double* slope, double* inv_hz) {
  using simd::v4d;
  auto lanes = [&](const v4d& k, v4d& s, v4d& inv) {
    const v4d x = d0[0] + k * dk[0], y = d0[1] + k * dk[1], z = d0[2] + k * dk[2];
    v4d h = x * x + y * y;
    for (int l = 0; l < 4; ++l) h[l] = std::sqrt(h[l]);
    h = h > 1e-12 ? h : v4d{} + 1e-12;  // std::max(sqrt, 1e-12)
    s = z / h;
    inv = 1.0 / h;
  };
  const double k0 = double(k_first), st = double(step);
  std::int64_t i = 0;
  for (; i + 4 <= count; i += 4) {
    const double b = double(i);
    v4d s, inv;
    lanes(k0 + st * (v4d{0, 1, 2, 3} + b), s, inv);
    std::memcpy(slope + i, &s, sizeof s);
    std::memcpy(inv_hz + i, &inv, sizeof inv);
  }
  if (i < count) {
    const double b = double(i);
    v4d s, inv;
    lanes(k0 + st * (v4d{0, 1, 2, 3} + b), s, inv);
    for (int l = 0; i + l < count; ++l) {
      slope[i + l] = s[l];
      inv_hz[i + l] = inv[l];
    }
  }
}

}  // namespace terrasprite
