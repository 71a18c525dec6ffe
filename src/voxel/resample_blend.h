// SPDX-License-Identifier: MIT
// The voxel renderer's resample, second half: blending each pixel's four
// intermediate-buffer samples (two columns, two sample rows) into colour and
// depth, the colour channels as one vector.
#pragma once
#include <cstddef>
#include <cstdint>

namespace terrasprite {

/// One sample of a vertical plane: packed RGBA8 colour and depth in metres
/// along the view axis (+inf = sky).
struct PlaneSample {
  std::uint32_t color;
  float depth;
};

/// One pixel's taps: columns L and L + s, sample rows kb and kb + 1.
struct ResampleTap {
  int x;              ///< pixel column in the row
  float fc, fk;       ///< weights of column L + s and of row kb + 1
  unsigned ok;        ///< bit 2a + b: column a holds sample kb + b
  std::size_t at[2];  ///< buffer index of sample kb of each column (modular arithmetic)
};

/// Writes each tap's pixel: colour (RGBA8) into `row` + 4 x, depth into
/// `depth` + x. Colour is the weighted mean of the samples present (sky
/// colour `sky` when none is), depth the weighted mean on a surface (all four
/// hit, spread within 30 % of the nearest) and otherwise the heaviest sample's.
void blend_taps(const ResampleTap* taps, int count, const PlaneSample* samples, std::uint32_t sky,
                std::uint8_t* row, float* depth);

}  // namespace terrasprite
