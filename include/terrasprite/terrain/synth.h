// SPDX-License-Identifier: MIT
// Synthetic mountains, for tests and for runs without a height file.
#pragma once
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// Seeded, deterministic mountains: fBm plus ridged noise, a few thermal
/// erosion passes, heights normalised to [0, relief_m]. size >= 2.
struct SynthOptions {
  int size = 513;  ///< samples per side
  double spacing_m = 30.0;
  double relief_m = 2000.0;
  unsigned seed = 1;
  int erosion_passes = 2;
};
Heightfield synthesize_terrain(const SynthOptions& o);

}  // namespace terrasprite
