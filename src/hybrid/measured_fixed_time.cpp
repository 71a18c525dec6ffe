// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/measured_fixed_time.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "terrasprite/common/stats.h"

namespace terrasprite {

MeasuredFixedTime::MeasuredFixedTime(int window, double cap)
    : window_(std::max(1, window)), cap_(std::max(0.0, cap)) {}

double MeasuredFixedTime::deviation(double ms) {
  if (!(ms > 0) || !std::isfinite(ms)) return 0;
  recent_.push_back(ms);
  while (int(recent_.size()) > window_) recent_.pop_front();
  const double usual = median(std::vector<double>(recent_.begin(), recent_.end()));
  const double d = std::clamp(ms - usual, -cap_ * usual, cap_ * usual);
  last_log_ratio_ = usual + d > 0 ? std::log((usual + d) / usual) : 0.0;
  return d;
}

}  // namespace terrasprite
