// SPDX-License-Identifier: MIT
// Internal to quality/: exact median of non-negative floats.
#pragma once
#include <cstdint>
#include <span>

namespace terrasprite::quality::detail {

/// Median of values[i] for which mask is empty or mask[i] != 0 (an even count
/// gives the mean of the two middle values, as numpy). Values must be >= 0 and
/// not NaN. Returns NaN when nothing is selected.
double median(std::span<const float> values, std::span<const std::uint8_t> mask);

}  // namespace terrasprite::quality::detail
