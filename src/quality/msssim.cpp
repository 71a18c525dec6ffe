// SPDX-License-Identifier: MIT
// MS-SSIM: Z. Wang, E. P. Simoncelli, A. C. Bovik, "Multi-scale structural
// similarity for image quality assessment", Asilomar 2003, Eq. (7) with the
// weights of Sec. 3.2. Contrast-structure at scales 1..4, full SSIM at scale 5,
// 2x2 average and decimate between scales.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "quality/ssim_core.h"
#include "terrasprite/common/error.h"

namespace terrasprite::quality {

namespace {

using detail::Plane;

constexpr int kScales = 5;
constexpr double kWeights[kScales] = {0.0448, 0.2856, 0.3001, 0.2363, 0.1333};
constexpr int kMinSide = 11 << (kScales - 1);  // the 11x11 window must fit the coarsest scale

Plane halve(const Plane& p) {
  Plane out(p.width / 2, p.height / 2);
  tbb::parallel_for(0, out.height, [&](int y) {
    const float* r0 = p.row(2 * y);
    const float* r1 = p.row(2 * y + 1);
    float* o = out.row(y);
    for (int x = 0; x < out.width; ++x)
      o[x] = 0.25f * (r0[2 * x] + r0[2 * x + 1] + r1[2 * x] + r1[2 * x + 1]);
  });
  return out;
}

// A coarse pixel stays scored when any child is: small masked regions (a
// disocclusion sliver) must not vanish at the coarse scales.
std::vector<std::uint8_t> halve_mask(const std::vector<std::uint8_t>& m, int width, int height) {
  if (m.empty()) return {};
  const int w = width / 2, h = height / 2;
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(2 * y) * width + 2 * x;
      out[static_cast<std::size_t>(y) * w + x] =
          (m[i] | m[i + 1] | m[i + width] | m[i + width + 1]) ? 1 : 0;
    }
  return out;
}

}  // namespace

double msssim(const ImageView& reference, const ImageView& test, Mask mask) {
  detail::check_inputs("msssim", reference, test, mask);
  if (std::min(reference.width, reference.height) < kMinSide)
    throw InputError(fmt::format(
        "msssim: {}x{} is too small: MS-SSIM needs at least {} pixels on the shorter side",
        reference.width, reference.height, kMinSide));
  Plane a = detail::extract(reference, detail::Channel::kLuma);
  Plane b = detail::extract(test, detail::Channel::kLuma);
  std::vector<std::uint8_t> m(mask.begin(), mask.end());
  double result = 1.0;
  for (int s = 0; s < kScales; ++s) {
    const detail::SsimSums sums = detail::ssim_wang_plane(a, b, m);
    if (sums.n == 0) return std::nan("");
    // Negative means (anti-correlated structure) would give a NaN power: clamp to 0.
    const double term = (s + 1 < kScales ? sums.cs : sums.ssim) / static_cast<double>(sums.n);
    result *= std::pow(std::max(0.0, term), kWeights[s]);
    if (s + 1 < kScales) {
      m = halve_mask(m, a.width, a.height);
      a = halve(a), b = halve(b);
    }
  }
  return result;
}

}  // namespace terrasprite::quality
