// SPDX-License-Identifier: MIT
// The rays of one intermediate-buffer column, four at a time: their slopes
// (rise per horizontal metre) and inverse horizontal lengths.
#pragma once
#include <cstdint>

namespace terrasprite {

/// Rays d = d0 + k dk for k = k_first + step i, i = 0 .. count - 1:
/// slope[i] = d.z / hz and inv_hz[i] = 1 / hz, hz = max(|(d.x, d.y)|, 1e-12).
/// The same arithmetic, lane by lane, as the scalar expressions.
void column_rays(const double d0[3], const double dk[3], std::int64_t k_first, int step,
                 std::int64_t count, double* slope, double* inv_hz);

}  // namespace terrasprite
