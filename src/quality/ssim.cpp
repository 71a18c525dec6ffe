// SPDX-License-Identifier: MIT
// ssim(): picks the planes (luma and R, G, B) and the kernel (Wang or
// ffmpeg). Wang's optional down-sampling follows his reference code
// ssim_index.m: f = max(1, round(min(M, N) / 256)), imfilter with an f x f
// box ('symmetric', 'same'), then every f-th pixel from the first.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "quality/filter.h"
#include "quality/ssim_core.h"

namespace terrasprite::quality {

namespace {

using detail::Channel;
using detail::Plane;

// MATLAB imfilter centres an even f x f kernel at floor((f + 1) / 2) (1-based),
// so the box kept for sample s covers s - (c - 1) .. s - (c - 1) + f - 1.
Plane downsample(const Plane& p, int f) {
  const int w = (p.width + f - 1) / f, h = (p.height + f - 1) / f;
  const int lead = (f + 1) / 2 - 1;
  Plane out(w, h);
  const float inv = 1.0f / static_cast<float>(f * f);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      float sum = 0;
      for (int j = 0; j < f; ++j) {
        const float* row = p.row(detail::reflect(y * f - lead + j, p.height));
        for (int i = 0; i < f; ++i) sum += row[detail::reflect(x * f - lead + i, p.width)];
      }
      out.row(y)[x] = sum * inv;
    }
  });
  return out;
}

std::vector<std::uint8_t> downsample_mask(Mask mask, int width, int height, int f) {
  if (mask.empty()) return {};
  const int w = (width + f - 1) / f, h = (height + f - 1) / f;
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out[static_cast<std::size_t>(y) * w + x] = mask[static_cast<std::size_t>(y) * f * width + x * f];
  return out;
}

double wang_channel(const ImageView& reference, const ImageView& test, Channel c, int f,
                    const std::vector<std::uint8_t>& mask) {
  Plane a = detail::extract(reference, c), b = detail::extract(test, c);
  if (f > 1) a = downsample(a, f), b = downsample(b, f);
  const detail::SsimSums s = detail::ssim_wang_plane(a, b, mask);
  return s.n ? s.ssim / static_cast<double>(s.n) : std::nan("");
}

std::vector<std::uint8_t> channel_bytes(const ImageView& v, int c) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(v.width) * v.height);
  const int k = v.channels == 1 ? 0 : c;
  tbb::parallel_for(0, v.height, [&](int y) {
    const std::uint8_t* src = v.row(y) + k;
    std::uint8_t* dst = out.data() + static_cast<std::size_t>(y) * v.width;
    for (int x = 0; x < v.width; ++x) dst[x] = src[static_cast<std::size_t>(x) * v.channels];
  });
  return out;
}

}  // namespace

SsimResult ssim(const ImageView& reference, const ImageView& test, const SsimOptions& options, Mask mask) {
  detail::check_inputs("ssim", reference, test, mask);
  SsimResult r;
  if (options.mode == SsimMode::kFfmpeg) {
    const std::vector<std::uint8_t> m(mask.begin(), mask.end());
    for (int c = 0; c < 3; ++c) {
      const auto a = channel_bytes(reference, c), b = channel_bytes(test, c);
      r.channels[c] = detail::ssim_ffmpeg_plane(a.data(), b.data(), reference.width, reference.height, m);
    }
    // ffmpeg's 'All' weights each plane by its share of the samples: equal here.
    r.ssim = (r.channels[0] + r.channels[1] + r.channels[2]) / 3.0;
    return r;
  }
  const int f = options.downsample
                    ? std::max(1, static_cast<int>(std::lround(std::min(reference.width, reference.height) / 256.0)))
                    : 1;
  const auto m = f > 1 ? downsample_mask(mask, reference.width, reference.height, f)
                       : std::vector<std::uint8_t>(mask.begin(), mask.end());
  r.ssim = wang_channel(reference, test, Channel::kLuma, f, m);
  if (options.channels) {
    const Channel rgb[3] = {Channel::kR, Channel::kG, Channel::kB};
    for (int c = 0; c < 3; ++c) r.channels[c] = wang_channel(reference, test, rgb[c], f, m);
  }
  return r;
}

}  // namespace terrasprite::quality
