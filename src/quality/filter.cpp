// SPDX-License-Identifier: MIT
// 1D convolution loops. Mirrored taps of symmetric and antisymmetric kernels
// (all of SSIM's and FLIP's) share one multiply. Blocks of 32 outputs are accumulated in four
// 8-float vectors across the taps (GCC vector extensions: one AVX register each in the AVX2 clone,
// two SSE registers in the baseline). Four independent accumulators hide the add latency. Every
// output sums its taps in the same order in both clones and in the scalar tail, so results do not
// depend on where a row is split.
// The fast clone is x86-64-v3 (AVX2 + FMA) and may contract w * x + acc into one fused
// multiply-add (the file's fp-contract=fast; the project's -std=c++20 otherwise keeps it off): one
// instruction instead of two per tap and one rounding instead of two. The baseline clone has no
// FMA, so results differ between the clones by float rounding only; within a clone the vector
// lanes and the scalar tail still contract alike (same code shape).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("fp-contract=fast")
#endif
#include "quality/filter.h"

#include <cmath>
#include <cstring>

#include "common/simd.h"

namespace terrasprite::quality::detail {

namespace {

// Internal helpers, always inlined: the ABI note about passing AVX vectors
// without AVX (the baseline clone) does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
using v8 = simd::v8f;

inline v8 load(const float* p) {
  v8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store(float* p, v8 v) {
  std::memcpy(p, &v, sizeof v);
}

}  // namespace

// The loops are written once over a "tap source" so the general, symmetric
// and antisymmetric cases share them; `at(k, x)` loads 8 floats of tap k.
namespace {

// One tap pair (k, taps-1-k) folded: w[k] * (a +- b).
template <int S>
inline v8 fold(v8 a, v8 b) {
  if constexpr (S > 0)
    return a + b;
  else
    return a - b;
}
template <int S>
inline float fold1(float a, float b) {
  if constexpr (S > 0)
    return a + b;
  else
    return a - b;
}

template <int S, typename At, typename At1>
inline void convolve(int n, const float* w, int taps, float* out, At at, At1 at1) {
  const int half = S == 0 ? taps : taps / 2;  // taps with their own multiply
  int x = 0;
  for (; x + 32 <= n; x += 32) {
    v8 a0 = {}, a1 = {}, a2 = {}, a3 = {};
    for (int k = 0; k < half; ++k) {
      const v8 wk = v8{} + w[k];
      if constexpr (S == 0) {
        a0 += wk * at(k, x), a1 += wk * at(k, x + 8), a2 += wk * at(k, x + 16),
            a3 += wk * at(k, x + 24);
      } else {
        const int m = taps - 1 - k;
        a0 += wk * fold<S>(at(k, x), at(m, x)), a1 += wk * fold<S>(at(k, x + 8), at(m, x + 8));
        a2 += wk * fold<S>(at(k, x + 16), at(m, x + 16)),
            a3 += wk * fold<S>(at(k, x + 24), at(m, x + 24));
      }
    }
    if constexpr (S > 0) {  // the centre tap
      const v8 wc = v8{} + w[half];
      a0 += wc * at(half, x), a1 += wc * at(half, x + 8), a2 += wc * at(half, x + 16),
          a3 += wc * at(half, x + 24);
    }
    store(out + x, a0), store(out + x + 8, a1), store(out + x + 16, a2), store(out + x + 24, a3);
  }
  for (; x < n; ++x) {  // same order of operations as the vector lanes
    float acc = 0;
    for (int k = 0; k < half; ++k)
      acc += S == 0 ? w[k] * at1(k, x) : w[k] * fold1<S>(at1(k, x), at1(taps - 1 - k, x));
    if constexpr (S > 0) acc += w[half] * at1(half, x);
    out[x] = acc;
  }
}

}  // namespace

TS_CLONES_V3 void filter_row(const float* in, int n, const float* w, int taps, float* out,
                             int symmetry) {
  auto at = [in](int k, int x) { return load(in + x + k); };
  auto at1 = [in](int k, int x) { return in[x + k]; };
  if (symmetry == kSymmetric)
    convolve<1>(n, w, taps, out, at, at1);
  else if (symmetry == kAntisymmetric)
    convolve<-1>(n, w, taps, out, at, at1);
  else
    convolve<0>(n, w, taps, out, at, at1);
}

TS_CLONES_V3 void filter_column(const float* const* rows, int taps, const float* w, int n,
                                float* out, int symmetry) {
  auto at = [rows](int k, int x) { return load(rows[k] + x); };
  auto at1 = [rows](int k, int x) { return rows[k][x]; };
  if (symmetry == kSymmetric)
    convolve<1>(n, w, taps, out, at, at1);
  else if (symmetry == kAntisymmetric)
    convolve<-1>(n, w, taps, out, at, at1);
  else
    convolve<0>(n, w, taps, out, at, at1);
}

void Kernel::find_symmetry() {
  bool sym = true, anti = w[radius] == 0.0f;
  for (int k = 0; k < radius; ++k) {
    sym = sym && w[k] == w[taps() - 1 - k];
    anti = anti && w[k] == -w[taps() - 1 - k];
  }
  symmetry = sym ? kSymmetric : (anti ? kAntisymmetric : kGeneral);
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
  k.find_symmetry();
  return k;
}

}  // namespace terrasprite::quality::detail
