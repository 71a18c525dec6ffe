// SPDX-License-Identifier: MIT
// Locating a row of pixels in the plane layout, four pixels at a time: in a
// slope-indexed layout (V far outside the image) the per-pixel division,
// with the scalar arithmetic (so the same bits); in a polar one, the angle
// around V and the radius.
#pragma once
#include <cstdint>

namespace terrasprite {

/// The slope layout's constants, as the renderer's scalar locate reads them.
struct SlopeRowLocator {
  double vx, vy, ex, ey, c0, inv_dc, inv_dr;
};

/// Pixels x0 .. x0 + count - 1 of row y: cf = (b / a - c0) * inv_dc - 0.5,
/// kf = a * inv_dr (a, b the pixel centre's coordinates along e and across it).
void locate_slope_row(const SlopeRowLocator& L, int y, int x0, int count, double* cf, double* kf);

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
