// SPDX-License-Identifier: MIT
// Wall-clock intervals on the steady clock, in milliseconds.
#pragma once
#include <chrono>

namespace terrasprite {

/// Milliseconds from `t0` to now on the steady clock.
inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace terrasprite
