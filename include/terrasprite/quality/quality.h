// SPDX-License-Identifier: MIT
// Image-quality metrics against a reference: PSNR, SSIM, MS-SSIM, FLIP.
// (Contract fixed here so renderers can code against it; implemented in src/quality/.)
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "terrasprite/common/image.h"

namespace terrasprite::quality {

/// Optional per-pixel mask: empty = every pixel counts; otherwise width*height
/// bytes, row 0 on top, tightly packed, non-zero = pixel is scored. Window-based
/// metrics score the windows whose centre pixel is in the mask. A mask of the
/// wrong size throws InputError; a mask that selects nothing gives NaN scores
/// (no pixel, no score) rather than a made-up value.
using Mask = std::span<const std::uint8_t>;

/// All metrics take the reference first; 8-bit values, peak 255. Views may be
/// 1, 3 or 4 channels (alpha ignored, grey replicated). Different sizes, or an
/// empty image, throw InputError with a message naming the sizes. The views are
/// only read during the call. Work is spread over TBB's threads (respecting any
/// tbb::global_control limit) and gives the same result for any thread count.

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
  /// Wang's reference code (ssim_index.m) first averages f x f boxes (symmetric
  /// padding, MATLAB imfilter 'same') and keeps every f-th pixel, with
  /// f = max(1, round(min(W,H)/256)), to mimic a viewing distance. Off by
  /// default: we score the pixels as rendered. kWang only.
  bool downsample = false;
  bool channels = true;  ///< kWang: also compute per R, G, B channel (kFfmpeg always does)
};
struct SsimResult {
  double ssim = 0;  ///< Wang: on luma; ffmpeg: its 'All' (weighted over channels)
  std::array<double, 3> channels{0, 0, 0};  ///< per R, G, B (when options.channels)
};
/// Mean SSIM over the scored windows. kWang needs 11 x 11 pixels (after any
/// down-sampling), kFfmpeg 8 x 8 (ffmpeg ignores trailing pixels beyond whole
/// 4 x 4 blocks, and so do we); smaller images throw InputError.
SsimResult ssim(const ImageView& reference, const ImageView& test, const SsimOptions& options = {},
                Mask mask = {});

/// MS-SSIM (Wang, Simoncelli, Bovik 2003), 5 scales on luma. Throws InputError
/// for images under 176 pixels on the shorter side. The mask is halved with the
/// image (a coarse pixel counts when any of its 2x2 children does).
double msssim(const ImageView& reference, const ImageView& test, Mask mask = {});

struct FlipOptions {
  double ppd = 67.02;     ///< pixels per degree of visual angle, in (0, 1000]
  bool want_map = false;  ///< fill FlipResult::map
};
struct FlipResult {
  double mean = 0;
  double median = 0;
  std::vector<float> map;  ///< width*height per-pixel error in [0, 1] when asked for
};
/// LDR-FLIP (Andersson et al. 2020): mean and median of the per-pixel error
/// over the masked pixels (median of an even count: mean of the two middle
/// values). The map, when asked for, covers every pixel, mask or not. A ppd
/// outside (0, 1000] throws InputError. Any size works (borders replicate).
FlipResult flip(const ImageView& reference, const ImageView& test, const FlipOptions& options = {},
                Mask mask = {});

/// Difference images (new RGBA8 images owned by the caller, alpha 255).

/// Per-channel |reference - test| * scale, clamped to 255 (scale 1 = raw
/// difference; the default 4 makes small errors visible). Throws as above,
/// and for a scale that is not finite and positive.
Image difference_image(const ImageView& reference, const ImageView& test, double scale = 4.0);

/// A FLIP map (values in [0, 1], clamped) shown with the magma colour map, as
/// the paper does. `map` holds width*height values, row 0 on top; a size
/// mismatch throws InputError.
Image flip_image(std::span<const float> map, int width, int height);

}  // namespace terrasprite::quality
