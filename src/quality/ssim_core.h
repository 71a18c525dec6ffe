// SPDX-License-Identifier: MIT
// Internal to quality/: the SSIM kernels shared by ssim() and msssim().
#pragma once
#include <cstdint>
#include <vector>

#include "quality/planes.h"

namespace terrasprite::quality::detail {

/// Sums over the scored windows of one plane pair: SSIM = l * cs, and the
/// contrast-structure term cs alone (MS-SSIM needs it at the finer scales).
struct SsimSums {
  double ssim = 0;
  double cs = 0;
  std::size_t n = 0;
};

/// Where SSIM reads its rows: a float plane, or a channel of an image converted
/// row by row as it is needed (no full-size copy).
struct RowSource {
  const Plane* plane = nullptr;
  const ImageView* image = nullptr;
  Channel channel = Channel::kLuma;

  int width() const { return plane ? plane->width : image->width; }
  int height() const { return plane ? plane->height : image->height; }
  /// Row y; `scratch` (width floats) is used when it must be converted.
  const float* row(int y, float* scratch) const {
    if (plane) return plane->row(y);
    extract_row(*image, channel, y, scratch);
    return scratch;
  }
};

/// Wang et al. 2004 on values on a 0..255 scale: 11x11 Gaussian, sigma 1.5,
/// biased moments, valid region only. `mask` is empty or width*height bytes;
/// a window counts when its centre pixel is set. Throws InputError when a
/// side is under 11 pixels.
SsimSums ssim_wang(const RowSource& a, const RowSource& b, const std::vector<std::uint8_t>& mask);
inline SsimSums ssim_wang_plane(const Plane& a, const Plane& b,
                                const std::vector<std::uint8_t>& mask) {
  return ssim_wang(RowSource{&a}, RowSource{&b}, mask);
}

/// ffmpeg's ssim filter (libavfilter/vf_ssim.c) on one 8-bit plane pair
/// (tightly packed, width*height bytes): mean over its overlapping 8x8 windows.
/// Throws InputError when a side is under 8 pixels.
double ssim_ffmpeg_plane(const std::uint8_t* a, const std::uint8_t* b, int width, int height,
                         const std::vector<std::uint8_t>& mask);

}  // namespace terrasprite::quality::detail
