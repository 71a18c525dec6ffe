// SPDX-License-Identifier: MIT
// Resampling a height field to another sample count over the same extent.
#pragma once
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// Bilinear resampling to width x height samples over the same extent.
Heightfield resample_heightfield(const Heightfield& h, int width, int height);

}  // namespace terrasprite
