// SPDX-License-Identifier: MIT
#include "terrasprite/measured_fixed_time.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace terrasprite {

MeasuredFixedTime::MeasuredFixedTime(int window, double cap)
    : window_(std::max(1, window)), cap_(std::max(0.0, cap)) {}

double MeasuredFixedTime::deviation(double ms) {
  if (!(ms > 0) || !std::isfinite(ms)) return 0;
  recent_.push_back(ms);
  while (int(recent_.size()) > window_) recent_.pop_front();
  std::vector<double> sorted(recent_.begin(), recent_.end());
  const auto mid = sorted.begin() + std::ptrdiff_t(sorted.size() / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  return std::clamp(ms - *mid, -cap_ * *mid, cap_ * *mid);
}

}  // namespace terrasprite
