// SPDX-License-Identifier: MIT
// Shared setup of the studies' in-process tests.
#pragma once
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

/// A small synthetic terrain of `samples`² heights, without erosion passes
/// (fast to make; the studies' tests need a terrain, not a realistic one).
inline Terrain tiny_synthetic_terrain(int samples) {
  TerrainOptions o;
  o.synthetic_size = samples;
  o.erosion_passes = 0;
  return load_terrain(o);
}

}  // namespace terrasprite
