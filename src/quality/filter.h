// SPDX-License-Identifier: MIT
// Internal to quality/: 1D convolution kernels, the inner loops of SSIM and
// FLIP's separable filters. Built for AVX2 and for the baseline, picked at
// run time (GCC function multi-versioning), so default flags stay portable.
#pragma once
#include <vector>

namespace terrasprite::quality::detail {

/// out[x] = sum_k w[k] * in[x + k] for x in [0, n): `in` holds n + taps - 1
/// values (the caller pads or reads a valid region).
void filter_row(const float* in, int n, const float* w, int taps, float* out);

/// out[x] = sum_k w[k] * rows[k][x] for x in [0, n).
void filter_column(const float* const* rows, int taps, const float* w, int n, float* out);

/// Index into [0, n) with whole-sample symmetric reflection (d c b a | a b c d),
/// as scipy's convolve2d boundary='symm' and MATLAB's 'symmetric'.
inline int reflect(int i, int n) {
  const int period = 2 * n;
  i %= period;
  if (i < 0) i += period;
  return i < n ? i : period - 1 - i;
}

/// padded[i] = in[reflect(i - r, n)] for i in [0, n + 2r).
void pad_reflect(const float* in, int n, int r, float* padded);

/// A 1D kernel with its radius (taps = 2 * radius + 1), centre at index radius.
struct Kernel {
  int radius = 0;
  std::vector<float> w;
  int taps() const { return 2 * radius + 1; }
};

/// Normalised Gaussian exp(-x^2 / (2 sigma^2)), x in pixels, |x| <= radius.
Kernel gaussian(double sigma, int radius);

}  // namespace terrasprite::quality::detail
