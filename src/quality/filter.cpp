// SPDX-License-Identifier: MIT
// 1D convolution loops. Blocks of 32 outputs are accumulated in four 8-float
// vectors across the taps (GCC vector extensions: one AVX register each in the
// AVX2 clone, two SSE registers in the baseline). Four independent
// accumulators hide the add latency. Every output sums its taps in the same
// order in both clones and in the scalar tail, so results do not depend on the
// CPU or on where a row is split.
#include "quality/filter.h"

#include <cmath>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TS_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TS_CLONES
#endif

namespace terrasprite::quality::detail {

namespace {

// Internal helpers, always inlined: the ABI note about passing AVX vectors
// without AVX (the baseline clone) does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
typedef float v8 __attribute__((vector_size(32)));

inline v8 load(const float* p) {
  v8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store(float* p, v8 v) {
  std::memcpy(p, &v, sizeof v);
}

}  // namespace

TS_CLONES void filter_row(const float* in, int n, const float* w, int taps, float* out) {
  int x = 0;
  for (; x + 32 <= n; x += 32) {
    v8 a0 = {}, a1 = {}, a2 = {}, a3 = {};
    for (int k = 0; k < taps; ++k) {
      const v8 wk = v8{} + w[k];
      const float* src = in + x + k;
      a0 += wk * load(src);
      a1 += wk * load(src + 8);
      a2 += wk * load(src + 16);
      a3 += wk * load(src + 24);
    }
    store(out + x, a0), store(out + x + 8, a1), store(out + x + 16, a2), store(out + x + 24, a3);
  }
  for (; x + 8 <= n; x += 8) {
    v8 a = {};
    for (int k = 0; k < taps; ++k) a += (v8{} + w[k]) * load(in + x + k);
    store(out + x, a);
  }
  for (; x < n; ++x) {
    float acc = 0;
    for (int k = 0; k < taps; ++k) acc += w[k] * in[x + k];
    out[x] = acc;
  }
}

TS_CLONES void filter_column(const float* const* rows, int taps, const float* w, int n,
                             float* out) {
  int x = 0;
  for (; x + 32 <= n; x += 32) {
    v8 a0 = {}, a1 = {}, a2 = {}, a3 = {};
    for (int k = 0; k < taps; ++k) {
      const v8 wk = v8{} + w[k];
      const float* src = rows[k] + x;
      a0 += wk * load(src);
      a1 += wk * load(src + 8);
      a2 += wk * load(src + 16);
      a3 += wk * load(src + 24);
    }
    store(out + x, a0), store(out + x + 8, a1), store(out + x + 16, a2), store(out + x + 24, a3);
  }
  for (; x + 8 <= n; x += 8) {
    v8 a = {};
    for (int k = 0; k < taps; ++k) a += (v8{} + w[k]) * load(rows[k] + x);
    store(out + x, a);
  }
  for (; x < n; ++x) {
    float acc = 0;
    for (int k = 0; k < taps; ++k) acc += w[k] * rows[k][x];
    out[x] = acc;
  }
}

Kernel gaussian(double sigma, int radius) {
  Kernel k;
  k.radius = radius;
  k.w.resize(k.taps());
  double sum = 0;
  std::vector<double> d(k.taps());
  for (int i = -radius; i <= radius; ++i)
    sum += d[i + radius] = std::exp(-(i * i) / (2 * sigma * sigma));
  for (int i = 0; i < k.taps(); ++i) k.w[i] = static_cast<float>(d[i] / sum);
  return k;
}

}  // namespace terrasprite::quality::detail
