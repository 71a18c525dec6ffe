// SPDX-License-Identifier: MIT
// Quadtree LOD levels of a height grid: which samples each level keeps.
#pragma once
#include <vector>

#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// Sample indices along one axis of n samples for pyramid level k: every
/// 2^k-th sample plus the last one (a narrower last quad when n - 1 is not a
/// multiple of 2^k), so no input size loses data. n >= 1, level >= 0.
std::vector<int> level_indices(int n, int level);

/// Sample indices along one axis for a coarse grid of `quads` quads:
/// round(q * (n - 1) / quads) for q = 0..quads. For n - 1 a multiple of
/// `quads` these are exactly every ((n - 1) / quads)-th sample (the paper's
/// 513 samples, 16 quads: every 32nd). quads is clamped to [1, n - 1].
std::vector<int> quad_indices(int n, int quads);

/// Number of pyramid levels down to (and including) the first level with
/// at most `min_quads` quads along the longer axis.
int level_count(const Heightfield& h, int min_quads = 1);

}  // namespace terrasprite
