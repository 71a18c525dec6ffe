// SPDX-License-Identifier: MIT
// Image-quality metrics against a reference: PSNR, SSIM, MS-SSIM, FLIP.
// (Contract fixed here so renderers can code against it; implemented in src/quality/.)
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "terrasprite/image.h"

namespace terrasprite::quality {

/// Optional per-pixel mask: empty = every pixel counts; otherwise width*height
/// bytes, row 0 on top, non-zero = pixel is scored. Window-based metrics score
/// the windows whose centre pixel is in the mask.
using Mask = std::span<const std::uint8_t>;

/// All metrics take the reference first. Views may be 1, 3 or 4 channels
/// (alpha ignored, grey replicated). Different sizes, or an empty image, throw
/// InputError with a message naming the sizes.

/// PSNR in dB, peak 255: over the MSE of R, G and B together, and on luma
/// (Y = 0.299 R + 0.587 G + 0.114 B, unrounded). Identical images give +inf.
struct PsnrResult {
  double rgb = 0;
  double luma = 0;
};
PsnrResult psnr(const ImageView& reference, const ImageView& test, Mask mask = {});

enum class SsimMode {
  kWang,    ///< Wang et al. 2004: 11x11 Gaussian (sigma 1.5), K1 0.01, K2 0.03, valid region
  kFfmpeg,  ///< ffmpeg's ssim filter: 8x8 windows from 4x4 block sums, step 4
};
struct SsimOptions {
  SsimMode mode = SsimMode::kWang;
  bool downsample = false;  ///< Wang's reference-code down-sampling by max(1, round(min(W,H)/256))
  bool channels = true;     ///< also compute per R, G, B channel
};
struct SsimResult {
  double ssim = 0;  ///< Wang: on luma; ffmpeg: its 'All' (weighted over channels)
  std::array<double, 3> channels{0, 0, 0};  ///< per R, G, B (when options.channels)
};
SsimResult ssim(const ImageView& reference, const ImageView& test, const SsimOptions& options = {},
                Mask mask = {});

/// MS-SSIM (Wang, Simoncelli, Bovik 2003), 5 scales on luma. Throws InputError
/// for images under 176 pixels on the shorter side.
double msssim(const ImageView& reference, const ImageView& test);

struct FlipOptions {
  double ppd = 67.02;     ///< pixels per degree of visual angle
  bool want_map = false;  ///< fill FlipResult::map
};
struct FlipResult {
  double mean = 0;
  double median = 0;
  std::vector<float> map;  ///< width*height per-pixel error in [0, 1] when asked for
};
/// LDR-FLIP (Andersson et al. 2020).
FlipResult flip(const ImageView& reference, const ImageView& test, const FlipOptions& options = {},
                Mask mask = {});

}  // namespace terrasprite::quality
