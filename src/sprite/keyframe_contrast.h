// SPDX-License-Identifier: MIT
// What a keyframe's texture makes of a geometric error: per coarse quad, how
// fast the keyframe's luminance changes (gradient) and how much it varies
// (standard deviation) over the quad's footprint in the keyframe. The
// contrast metric (ErrorMetric::kContrast) turns a sample's displacement d
// (pixels) into a predicted intensity error min(gradient * d, sqrt(2) * sd):
// a small shift of a smooth ramp errs by slope times shift, a shift past the
// texture's features by at most the difference of two unrelated samples.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/sprite/error_metric.h"

namespace terrasprite {

/// Per quad of `grid` (row-major): RMS luminance gradient (grey levels 0-255
/// per pixel) and luminance standard deviation (grey levels) over the
/// bounding box of the quad's corners and centre projected into `key`'s
/// width x height image `rgba` (RGBA8, top row first, alpha 0 = sky, which
/// counts as the sky colour the sprite shows there). A quad with a point
/// behind the key's eye or a box outside the image gets 0 for both.
/// `rgba` must hold width * height * 4 bytes.
struct QuadContrast {
  std::vector<float> gradient;   ///< grey levels per pixel
  std::vector<float> deviation;  ///< grey levels
};
QuadContrast quad_contrast(const CoarseGrid& grid, const Camera& key, int width, int height,
                           std::span<const std::uint8_t> rgba);

}  // namespace terrasprite
