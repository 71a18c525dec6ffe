// SPDX-License-Identifier: MIT
// SSIM: Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality
// assessment: from error visibility to structural similarity", IEEE TIP 2004,
// Eq. (13) with the Gaussian-weighted moments of Eq. (14)-(16) (K1 .01, K2 .03).
//
// Streaming, separable: each worker takes a band of output rows and keeps the
// last 11 horizontally filtered rows of the moment inputs in a ring, so every
// input row is filtered once per band and the working set stays in cache.
// Eq. (13) needs sigma_x^2 + sigma_y^2 only as a sum, so x^2 + y^2 is
// filtered as one plane: four planes (x, y, x^2 + y^2, xy), not five.
#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>

#include "common/simd.h"
#include "quality/filter.h"
#include "quality/ssim_core.h"
#include "terrasprite/common/error.h"

namespace terrasprite::quality::detail {

namespace {

constexpr int kWindow = 11;
constexpr int kRadius = kWindow / 2;
// Output rows per work item, at least. Each band filters 2 * kRadius extra
// input rows, so bands are made as tall as load balance allows (four per
// thread); the ring is the same size for any band height.
constexpr int kBand = 64;
// Values are shifted by -128 before squaring: variances are differences of
// large squares, and centring the data keeps more float bits for them.
constexpr float kShift = 128.0f;
constexpr int kPlanes = 4;  // x, y, x^2 + y^2, xy
constexpr float kC1 = (0.01f * 255) * (0.01f * 255);
constexpr float kC2 = (0.03f * 255) * (0.03f * 255);

// The per-pixel loops, built for AVX2 and the baseline like filter.cpp's, with
// restrict pointers so GCC vectorises them without alias checks.
TS_CLONES_AVX2 void products(const float* __restrict a, const float* __restrict b, int n,
                             float* __restrict x, float* __restrict y, float* __restrict sq,
                             float* __restrict xy) {
  for (int i = 0; i < n; ++i) {
    const float p = a[i] - kShift, q = b[i] - kShift;
    x[i] = p, y[i] = q, sq[i] = p * p + q * q, xy[i] = p * q;
  }
}

#pragma GCC diagnostic ignored "-Wpsabi"  // vectors stay inside always-inlined code
using simd::v4d;
using simd::v4f;

// SSIM and its contrast-structure term from the filtered moments (Eq. 13).
TS_CLONES_AVX2 void ssim_terms(const float* __restrict m1, const float* __restrict m2,
                               const float* __restrict esq, const float* __restrict e12, int n,
                               float* __restrict s, float* __restrict c) {
  for (int i = 0; i < n; ++i) {
    const float mu1 = m1[i] + kShift, mu2 = m2[i] + kShift;
    // Bracketed so that x == y gives exactly 2 (E[x^2] - mu^2) == 2 cov: SSIM 1.
    const float vsum = esq[i] - (m1[i] * m1[i] + m2[i] * m2[i]), v12 = e12[i] - m1[i] * m2[i];
    const float l = (2 * mu1 * mu2 + kC1) / (mu1 * mu1 + mu2 * mu2 + kC1);
    const float cs = (2 * v12 + kC2) / (vsum + kC2);
    c[i] = cs;
    s[i] = l * cs;
  }
}

// Row sums of s and c in double. A plain `sum += s[i]` is one serial chain
// of scalar double adds (GCC may not reorder it without -ffast-math), which
// cost as much as Eq. 13 itself; four-lane double accumulators give the same
// sums up to double rounding (~1e-16 relative).
TS_CLONES_AVX2 void row_sums(const float* __restrict s, const float* __restrict c, int n,
                             double& ss, double& cs) {
  v4d as = {}, ac = {};
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    v4f vs, vc;
    __builtin_memcpy(&vs, s + i, sizeof vs);
    __builtin_memcpy(&vc, c + i, sizeof vc);
    as += __builtin_convertvector(vs, v4d);
    ac += __builtin_convertvector(vc, v4d);
  }
  double ts = (as[0] + as[1]) + (as[2] + as[3]), tc = (ac[0] + ac[1]) + (ac[2] + ac[3]);
  for (; i < n; ++i) ts += s[i], tc += c[i];
  ss = ts, cs = tc;
}

}  // namespace

SsimSums ssim_wang(const RowSource& a, const RowSource& b, const std::vector<std::uint8_t>& mask) {
  const int w = a.width(), h = a.height();
  if (w < kWindow || h < kWindow)
    throw InputError(fmt::format("ssim: {}x{} is smaller than the 11x11 SSIM window", w, h));
  const int ow = w - 2 * kRadius, oh = h - 2 * kRadius;
  static const Kernel g = gaussian(1.5, kRadius);
  std::vector<SsimSums> rows(oh);

  const int threads = tbb::this_task_arena::max_concurrency();
  const int band_h = std::max(kBand, (oh + 4 * threads - 1) / (4 * threads));
  const int bands = (oh + band_h - 1) / band_h;
  tbb::parallel_for(0, bands, [&](int band) {
    const int y0 = band * band_h, y1 = std::min(oh, y0 + band_h);
    // ring[plane][slot]: horizontally filtered input rows, ow floats each.
    std::vector<float> ring(static_cast<std::size_t>(kPlanes) * kWindow * ow);
    auto slot = [&](int plane, int r) {
      return ring.data() + (static_cast<std::size_t>(plane) * kWindow + r % kWindow) * ow;
    };
    std::vector<float> in(static_cast<std::size_t>(kPlanes) * w);
    std::vector<float> sa(w), sb(w);  // rows converted from an image
    std::vector<float> out(static_cast<std::size_t>(kPlanes) * ow);
    std::vector<float> s(ow);
    std::vector<float> c(ow);
    std::array<const float*, kWindow> ptr;

    for (int r = y0; r < y1 + 2 * kRadius; ++r) {
      float* x = in.data();
      products(a.row(r, sa.data()), b.row(r, sb.data()), w, x, x + w, x + 2 * w, x + 3 * w);
      for (int p = 0; p < kPlanes; ++p)
        filter_row(in.data() + static_cast<std::size_t>(p) * w, ow, g.w.data(), kWindow, slot(p, r),
                   g.symmetry);
      if (r < y0 + 2 * kRadius) continue;

      const int oy = r - 2 * kRadius;  // output row: window rows oy .. oy + 10
      for (int p = 0; p < kPlanes; ++p) {
        for (int k = 0; k < kWindow; ++k) ptr[k] = slot(p, oy + k);
        filter_column(ptr.data(), kWindow, g.w.data(), ow,
                      out.data() + static_cast<std::size_t>(p) * ow, g.symmetry);
      }
      const float* m1 = out.data();
      ssim_terms(m1, m1 + ow, m1 + 2 * ow, m1 + 3 * ow, ow, s.data(), c.data());
      SsimSums acc;
      const std::uint8_t* m =
          mask.empty() ? nullptr
                       : mask.data() + static_cast<std::size_t>(oy + kRadius) * w + kRadius;
      if (!m) {
        row_sums(s.data(), c.data(), ow, acc.ssim, acc.cs);
        acc.n = static_cast<std::size_t>(ow);
      } else {
        for (int i = 0; i < ow; ++i)
          if (m[i]) acc.ssim += s[i], acc.cs += c[i], ++acc.n;
      }
      rows[oy] = acc;
    }
  });
  SsimSums total;
  for (const SsimSums& r : rows) total.ssim += r.ssim, total.cs += r.cs, total.n += r.n;
  return total;
}

}  // namespace terrasprite::quality::detail
