// SPDX-License-Identifier: MIT
// SSIM: Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality
// assessment: from error visibility to structural similarity", IEEE TIP 2004,
// Eq. (13) with the Gaussian-weighted moments of Eq. (14)-(16) (K1 .01, K2 .03).
//
// Streaming, separable: each worker takes a band of output rows and keeps the
// last 11 horizontally filtered rows of the five moment inputs (x, y, x^2,
// y^2, xy) in a ring, so every input row is filtered once per band and the
// working set stays in cache.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

#include "quality/filter.h"
#include "quality/ssim_core.h"
#include "terrasprite/error.h"

namespace terrasprite::quality::detail {

namespace {

constexpr int kWindow = 11;
constexpr int kRadius = kWindow / 2;
constexpr int kBand = 64;  // output rows per work item
// Values are shifted by -128 before squaring: variances are differences of
// large squares, and centring the data keeps more float bits for them.
constexpr float kShift = 128.0f;
constexpr float kC1 = (0.01f * 255) * (0.01f * 255);
constexpr float kC2 = (0.03f * 255) * (0.03f * 255);

}  // namespace

SsimSums ssim_wang_plane(const Plane& a, const Plane& b, const std::vector<std::uint8_t>& mask) {
  const int w = a.width, h = a.height;
  if (w < kWindow || h < kWindow)
    throw InputError(fmt::format("ssim: {}x{} is smaller than the 11x11 SSIM window", w, h));
  const int ow = w - 2 * kRadius, oh = h - 2 * kRadius;
  static const Kernel g = gaussian(1.5, kRadius);
  std::vector<SsimSums> rows(oh);

  const int bands = (oh + kBand - 1) / kBand;
  tbb::parallel_for(0, bands, [&](int band) {
    const int y0 = band * kBand, y1 = std::min(oh, y0 + kBand);
    // ring[plane][slot]: horizontally filtered input rows, ow floats each.
    std::vector<float> ring(static_cast<std::size_t>(5) * kWindow * ow);
    auto slot = [&](int plane, int r) { return ring.data() + (static_cast<std::size_t>(plane) * kWindow + r % kWindow) * ow; };
    std::vector<float> in(static_cast<std::size_t>(5) * w);
    std::vector<float> out(static_cast<std::size_t>(5) * ow);
    std::vector<float> s(ow);
    std::vector<float> c(ow);
    std::array<const float*, kWindow> ptr;

    for (int r = y0; r < y1 + 2 * kRadius; ++r) {
      const float* ar = a.row(r);
      const float* br = b.row(r);
      float* x = in.data();
      float* y = x + w;
      float* xx = y + w;
      float* yy = xx + w;
      float* xy = yy + w;
      for (int i = 0; i < w; ++i) {
        const float p = ar[i] - kShift, q = br[i] - kShift;
        x[i] = p, y[i] = q, xx[i] = p * p, yy[i] = q * q, xy[i] = p * q;
      }
      for (int p = 0; p < 5; ++p) filter_row(in.data() + static_cast<std::size_t>(p) * w, ow, g.w.data(), kWindow, slot(p, r));
      if (r < y0 + 2 * kRadius) continue;

      const int oy = r - 2 * kRadius;  // output row: window rows oy .. oy + 10
      for (int p = 0; p < 5; ++p) {
        for (int k = 0; k < kWindow; ++k) ptr[k] = slot(p, oy + k);
        filter_column(ptr.data(), kWindow, g.w.data(), ow, out.data() + static_cast<std::size_t>(p) * ow);
      }
      const float* m1 = out.data();
      const float* m2 = m1 + ow;
      const float* e11 = m2 + ow;
      const float* e22 = e11 + ow;
      const float* e12 = e22 + ow;
      for (int i = 0; i < ow; ++i) {
        const float mu1 = m1[i] + kShift, mu2 = m2[i] + kShift;
        const float v1 = e11[i] - m1[i] * m1[i], v2 = e22[i] - m2[i] * m2[i], v12 = e12[i] - m1[i] * m2[i];
        const float l = (2 * mu1 * mu2 + kC1) / (mu1 * mu1 + mu2 * mu2 + kC1);
        c[i] = (2 * v12 + kC2) / (v1 + v2 + kC2);
        s[i] = l * c[i];
      }
      SsimSums acc;
      const std::uint8_t* m = mask.empty() ? nullptr : mask.data() + static_cast<std::size_t>(oy + kRadius) * w + kRadius;
      for (int i = 0; i < ow; ++i) {
        if (m && !m[i]) continue;
        acc.ssim += s[i], acc.cs += c[i], ++acc.n;
      }
      rows[oy] = acc;
    }
  });
  SsimSums total;
  for (const SsimSums& r : rows) total.ssim += r.ssim, total.cs += r.cs, total.n += r.n;
  return total;
}

}  // namespace terrasprite::quality::detail
