// SPDX-License-Identifier: MIT
// 1D convolution loops. Blocks of 16 outputs are accumulated in registers
// across the taps, which GCC turns into two 8-wide vectors per tap.
#include "quality/filter.h"

#include <cmath>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TS_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TS_CLONES
#endif

namespace terrasprite::quality::detail {

namespace {
constexpr int kBlock = 16;
}

TS_CLONES void filter_row(const float* in, int n, const float* w, int taps, float* out) {
  int x = 0;
  for (; x + kBlock <= n; x += kBlock) {
    float acc[kBlock] = {};
    for (int k = 0; k < taps; ++k) {
      const float wk = w[k];
      const float* src = in + x + k;
      for (int j = 0; j < kBlock; ++j) acc[j] += wk * src[j];
    }
    for (int j = 0; j < kBlock; ++j) out[x + j] = acc[j];
  }
  for (; x < n; ++x) {
    float acc = 0;
    for (int k = 0; k < taps; ++k) acc += w[k] * in[x + k];
    out[x] = acc;
  }
}

TS_CLONES void filter_column(const float* const* rows, int taps, const float* w, int n, float* out) {
  int x = 0;
  for (; x + kBlock <= n; x += kBlock) {
    float acc[kBlock] = {};
    for (int k = 0; k < taps; ++k) {
      const float wk = w[k];
      const float* src = rows[k] + x;
      for (int j = 0; j < kBlock; ++j) acc[j] += wk * src[j];
    }
    for (int j = 0; j < kBlock; ++j) out[x + j] = acc[j];
  }
  for (; x < n; ++x) {
    float acc = 0;
    for (int k = 0; k < taps; ++k) acc += w[k] * rows[k][x];
    out[x] = acc;
  }
}

void pad_reflect(const float* in, int n, int r, float* padded) {
  for (int i = 0; i < r; ++i) padded[i] = in[reflect(i - r, n)];
  for (int i = 0; i < n; ++i) padded[r + i] = in[i];
  for (int i = 0; i < r; ++i) padded[r + n + i] = in[reflect(n + i, n)];
}

Kernel gaussian(double sigma, int radius) {
  Kernel k;
  k.radius = radius;
  k.w.resize(k.taps());
  double sum = 0;
  std::vector<double> d(k.taps());
  for (int i = -radius; i <= radius; ++i) sum += d[i + radius] = std::exp(-(i * i) / (2 * sigma * sigma));
  for (int i = 0; i < k.taps(); ++i) k.w[i] = static_cast<float>(d[i] / sum);
  return k;
}

}  // namespace terrasprite::quality::detail
