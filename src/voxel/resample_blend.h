// SPDX-License-Identifier: MIT
// The voxel renderer's resample, second half: blending each pixel's four
// intermediate-buffer samples (two columns, two sample rows) into colour and
// depth. Eight pixels at a time with AVX2 where the CPU has it (gathers keep
// the buffer reads of many pixels in flight), else one pixel at a time; the
// two give the same bits.
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

/// The taps of up to kMax consecutive pixels of a row, x0 .. x0 + count - 1,
/// as a structure of arrays (pixel i in slot i): columns L and L + s, sample
/// rows kb and kb + 1. Storage lives in the struct (about 1.5 KB).
struct ResampleTaps {
  static constexpr int kMax = 64;
  int x0 = 0, count = 0;
  float fc[kMax], fk[kMax];  ///< weights of column L + s and of row kb + 1
  std::uint32_t ok[kMax];    ///< bit 2a + b: column a holds sample kb + b
  /// Buffer index of sample kb of column a (a = 0: L, 1: L + s); read only
  /// where `ok` says the sample is there (else any value).
  std::size_t at[2][kMax];
};

/// Writes each tap's pixel: colour (RGBA8) into `row` + 4 x, depth into
/// `depth` + x. Colour is the weighted mean of the samples present (sky
/// colour `sky` when none is), depth the weighted mean on a surface (all four
/// hit, spread within 30 % of the nearest) and otherwise the heaviest sample's.
/// `samples` holds `sample_count` samples; every index `ok` marks is below it.
void blend_taps(const ResampleTaps& taps, const PlaneSample* samples, std::size_t sample_count,
                std::uint32_t sky, std::uint8_t* row, float* depth);

/// The one-pixel-at-a-time blend (the reference the AVX2 kernel matches bit
/// for bit; blend_taps picks between them).
void blend_taps_scalar(const ResampleTaps& taps, const PlaneSample* samples, std::uint32_t sky,
                       std::uint8_t* row, float* depth);

/// The AVX2 kernel, eight pixels at a time with masked gathers (the tail one
/// at a time). Only where simd::has_avx2() and sample_count < 2^31; false
/// (nothing written) where the build has no AVX2 target.
bool blend_taps_avx2(const ResampleTaps& taps, const PlaneSample* samples, std::uint32_t sky,
                     std::uint8_t* row, float* depth);

}  // namespace terrasprite
