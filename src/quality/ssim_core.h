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

/// Wang et al. 2004 on float planes (values on a 0..255 scale): 11x11 Gaussian,
/// sigma 1.5, biased moments, valid region only. `mask` is empty or
/// width*height bytes; a window counts when its centre pixel is set.
/// Throws InputError when a side is under 11 pixels.
SsimSums ssim_wang_plane(const Plane& a, const Plane& b, const std::vector<std::uint8_t>& mask);

/// ffmpeg's ssim filter (libavfilter/vf_ssim.c) on one 8-bit plane pair
/// (tightly packed, width*height bytes): mean over its overlapping 8x8 windows.
/// Throws InputError when a side is under 8 pixels.
double ssim_ffmpeg_plane(const std::uint8_t* a, const std::uint8_t* b, int width, int height,
                         const std::vector<std::uint8_t>& mask);

}  // namespace terrasprite::quality::detail
