// SPDX-License-Identifier: MIT
// A plain `sum += v[i]` in double is one serial chain of scalar adds (GCC may
// not reorder it without -ffast-math): ~4 cycles a pixel, as much as some of
// FLIP's filters. Four-lane double accumulators (two vectors) give the same
// sum up to double rounding (~1e-16 relative), whatever the CPU: every clone
// adds in the same order.
#include "quality/row_sum.h"

#include "common/simd.h"

namespace terrasprite::quality::detail {

namespace {
#pragma GCC diagnostic ignored "-Wpsabi"  // vectors stay inside this function
using simd::v4d;
using simd::v4f;
using simd::v4i;
}  // namespace

TS_CLONES_AVX2 double row_sum(const float* v, const std::uint8_t* mask, int n) {
  v4d a = {}, b = {};
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    v4f x, y;
    __builtin_memcpy(&x, v + i, sizeof x);
    __builtin_memcpy(&y, v + i + 4, sizeof y);
    if (mask) {  // zero the unselected lanes
      const v4i mx = {mask[i], mask[i + 1], mask[i + 2], mask[i + 3]};
      const v4i my = {mask[i + 4], mask[i + 5], mask[i + 6], mask[i + 7]};
      x = mx != 0 ? x : v4f{};
      y = my != 0 ? y : v4f{};
    }
    a += __builtin_convertvector(x, v4d);
    b += __builtin_convertvector(y, v4d);
  }
  a += b;
  double s = (a[0] + a[1]) + (a[2] + a[3]);
  for (; i < n; ++i) s += (mask && !mask[i]) ? 0.0 : v[i];
  return s;
}

}  // namespace terrasprite::quality::detail
