// SPDX-License-Identifier: MIT
// Locating a row of pixels in a slope-indexed plane layout (V far outside the
// image), several pixels at a time: the resample's per-pixel division and
// floor, vectorised with the same arithmetic (so the same bits) as the scalar
// locate in voxel_renderer.cpp.
#pragma once
#include <cstdint>

namespace terrasprite {

/// The slope layout's constants, as the renderer's scalar locate reads them.
struct SlopeRowLocator {
  double vx, vy, ex, ey, c0, inv_dc, inv_dr;
  int key_max;  ///< keys are floor(cf) clamped to [-1, key_max]
};

/// Pixels x0 .. x0 + count - 1 of row y: cf = (b / a - c0) * inv_dc - 0.5,
/// kf = a * inv_dr (a, b the pixel centre's coordinates along e and across it)
/// and key = clamp(floor(cf), -1, key_max).
void locate_slope_row(const SlopeRowLocator& L, int y, int x0, int count, double* cf, double* kf,
                      std::int32_t* key);

/// The polar layout's constants (angle around V from the axis e).
struct PolarRowLocator {
  double vx, vy, ex, ey, c0, inv_dc, inv_dr;
  bool wrap;  ///< angles in [0, 2 pi) instead of (-pi, pi]
};

/// Pixels x0 .. x0 + count - 1 of row y: cf = (angle - c0) * inv_dc - 0.5 and
/// kf = radius * inv_dr, the angle from a vectorised atan2 (Cephes' rational
/// atan, within 2e-16 rad of libm's, no call per pixel).
void locate_polar_row(const PolarRowLocator& L, int y, int x0, int count, double* cf, double* kf);

}  // namespace terrasprite
