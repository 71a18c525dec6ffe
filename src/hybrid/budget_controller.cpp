// SPDX-License-Identifier: MIT
// Feed-forward from the cost model (budget = target / the smoothed
// measured-to-predicted ratio) plus a PI term on the measured error.
#include "terrasprite/budget_controller.h"

#include <algorithm>
#include <cmath>

namespace terrasprite {

BudgetController::BudgetController(const BudgetControllerOptions& options)
    : o_(options), budget_ms_(options.target_ms) {}

void BudgetController::update(double predicted_ms, double measured_ms) {
  if (!(predicted_ms > 0) || !(measured_ms > 0)) return;
  const double r = measured_ms / predicted_ms;
  const bool surprise = !first_ && r > o_.outlier_factor * ratio_;
  if (!surprise) {
    // Log-domain smoothing: a ratio of 2 and one of 0.5 weigh alike.
    ratio_ = first_ ? r
                    : std::exp((1 - o_.ratio_smoothing) * std::log(ratio_) +
                               o_.ratio_smoothing * std::log(r));
    first_ = false;
    const double error = std::clamp((o_.target_ms - measured_ms) / o_.target_ms, -1.0, 1.0);
    integral_ = std::clamp(integral_ + o_.ki * error, -o_.integral_limit, o_.integral_limit);
    const double correction = std::max(0.1, 1.0 + o_.kp * error + integral_);
    budget_ms_ = o_.target_ms / ratio_ * correction;
  }
}

void QualityStepController::update(double measured_ms) {
  if (measured_ms > o_.target_ms)
    quality_ -= o_.step;
  else if (measured_ms < 0.9 * o_.target_ms)
    quality_ += o_.step;
  quality_ = std::clamp(quality_, o_.min_quality, o_.max_quality);
}

}  // namespace terrasprite
