// SPDX-License-Identifier: MIT
// The march's colour pass, four hits at a time: each hit's bilinear colour
// read from one whole pyramid level, with the scalar reader's arithmetic.
#pragma once
#include <cstddef>
#include <cstdint>

#include "voxel/column_march.h"

namespace terrasprite {

/// One level's colour samples, in memory whole: sample (i, j) is
/// color[off + j * stride + i], 0 <= i < width, 0 <= j < height (both >= 2).
struct LevelColors {
  const std::uint32_t* color = nullptr;
  std::ptrdiff_t off = 0, stride = 0;
  int width = 0, height = 0;
};

/// Where the hits lie: hit k at level coordinates
/// ((u0 + t[k] du) scale, (v0 + t[k] dv) scale), t[k] in metres along the plane.
struct HitLine {
  double u0, v0, du, dv, scale;
};

/// Writes hits[k].color for k < the returned count, a multiple of 4 (0 where
/// the CPU lacks AVX2 or the level's indices do not fit 32 bits): the colour
/// BasicTileReader::bilinear_color gives at that point, bit for bit (clamped
/// into the level; 8-bit weights). The caller colours the rest. t[k] must be
/// finite.
std::size_t hit_colors(const LevelColors& level, const HitLine& line, const double* t,
                       MarchHit* hits, std::size_t count);

}  // namespace terrasprite
