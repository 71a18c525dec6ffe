// SPDX-License-Identifier: MIT
// Internal to quality/: the double sum of a float row, optionally masked.
#pragma once
#include <cstdint>

namespace terrasprite::quality::detail {

/// Sum of v[i] (in double) for i in [0, n) where mask is null or mask[i] != 0.
double row_sum(const float* v, const std::uint8_t* mask, int n);

}  // namespace terrasprite::quality::detail
