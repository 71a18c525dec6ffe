// SPDX-License-Identifier: MIT
// ffmpeg-compatible SSIM: the arithmetic of libavfilter/vf_ssim.c (itself
// from x264): 4x4 block sums of a, b, a^2 + b^2 and ab; each 8x8 window (2x2
// blocks, step 4) scored in 32-bit integers with constants scaled by 64 and
// 64*63, the division in float; mean over the windows of the plane. This is
// not Wang's Gaussian SSIM: it exists so we can check ourselves against the
// ffmpeg CLI.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>

#include "quality/ssim_core.h"
#include "terrasprite/common/error.h"

namespace terrasprite::quality::detail {

namespace {

using Sum = std::array<int, 4>;  // s1, s2, ss, s12 as in vf_ssim.c

// ssim_end1 of vf_ssim.c, 8-bit: the same integer constants and casts.
float ssim_end1(int s1, int s2, int ss, int s12) {
  constexpr int c1 = static_cast<int>(.01 * .01 * 255 * 255 * 64 + .5);
  constexpr int c2 = static_cast<int>(.03 * .03 * 255 * 255 * 64 * 63 + .5);
  const int vars = ss * 64 - s1 * s1 - s2 * s2;
  const int covar = s12 * 64 - s1 * s2;
  return static_cast<float>(2 * s1 * s2 + c1) * static_cast<float>(2 * covar + c2) /
         (static_cast<float>(s1 * s1 + s2 * s2 + c1) * static_cast<float>(vars + c2));
}

}  // namespace

double ssim_ffmpeg_plane(const std::uint8_t* a, const std::uint8_t* b, int width, int height,
                         const std::vector<std::uint8_t>& mask) {
  if (width < 8 || height < 8)
    throw InputError(
        fmt::format("ssim: {}x{} is smaller than ffmpeg's 8x8 SSIM window", width, height));
  const int bw = width >> 2,
            bh = height >> 2;  // trailing pixels beyond a whole block are ignored, as in ffmpeg
  std::vector<Sum> blocks(static_cast<std::size_t>(bw) * bh);
  tbb::parallel_for(0, bh, [&](int by) {
    for (int bx = 0; bx < bw; ++bx) {
      unsigned s1 = 0, s2 = 0, ss = 0, s12 = 0;
      for (int y = 0; y < 4; ++y) {
        const std::size_t o = static_cast<std::size_t>(4 * by + y) * width + 4 * bx;
        for (int x = 0; x < 4; ++x) {
          const unsigned p = a[o + x], q = b[o + x];
          s1 += p, s2 += q, ss += p * p + q * q, s12 += p * q;
        }
      }
      blocks[static_cast<std::size_t>(by) * bw + bx] = {int(s1), int(s2), int(ss), int(s12)};
    }
  });
  // Per window row: sum in double over the windows, as ssim_endn does.
  std::vector<double> rows(bh - 1, 0.0);
  std::vector<std::size_t> counts(bh - 1, 0);
  tbb::parallel_for(0, bh - 1, [&](int by) {
    const Sum* s0 = blocks.data() + static_cast<std::size_t>(by) * bw;
    const Sum* s1 = s0 + bw;
    const std::uint8_t* m =
        mask.empty() ? nullptr : mask.data() + static_cast<std::size_t>(4 * by + 4) * width;
    double acc = 0;
    std::size_t n = 0;
    for (int i = 0; i < bw - 1; ++i) {
      if (m && !m[4 * i + 4]) continue;  // window centre pixel
      Sum t;
      for (int k = 0; k < 4; ++k) t[k] = s0[i][k] + s0[i + 1][k] + s1[i][k] + s1[i + 1][k];
      acc += ssim_end1(t[0], t[1], t[2], t[3]);
      ++n;
    }
    rows[by] = acc;
    counts[by] = n;
  });
  double total = 0;
  std::size_t n = 0;
  for (int i = 0; i < bh - 1; ++i) total += rows[i], n += counts[i];
  return n ? total / static_cast<double>(n) : std::nan("");
}

}  // namespace terrasprite::quality::detail
