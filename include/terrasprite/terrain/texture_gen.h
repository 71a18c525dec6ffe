// SPDX-License-Identifier: MIT
// Generated drape textures: the default when no texture is given, and the
// LOD-sprite paper's checkerboard.
#pragma once
#include "terrasprite/common/image.h"
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// Elevation colour ramp times hillshade, sampled at texel centres over the
/// height samples' extent (Terrain's mapping). width, height >= 1.
Image derived_texture(const Heightfield& h, int width, int height);
Image derived_texture(const HeightSampler& h, int width, int height);

/// The paper's red/green checkerboard (its Fig. 13): `squares` per side.
Image checker_texture(int squares, int size_px);

}  // namespace terrasprite
