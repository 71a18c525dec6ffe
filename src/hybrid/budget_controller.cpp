// SPDX-License-Identifier: MIT
// Feed-forward from the cost model (budget = target / the smoothed
// measured-to-predicted ratio) plus a PI term on the measured error.
#include "terrasprite/hybrid/budget_controller.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace terrasprite {

namespace {

/// A normal's sigma from a sample, robustly: median absolute deviation / 0.6745.
double robust_sigma(const std::deque<double>& sample) {
  std::vector<double> e(sample.begin(), sample.end());
  if (e.empty()) return 0.0;
  const auto mid = e.begin() + std::ptrdiff_t(e.size() / 2);
  std::nth_element(e.begin(), mid, e.end());
  const double m = *mid;
  for (double& x : e) x = std::abs(x - m);
  std::nth_element(e.begin(), mid, e.end());
  return *mid / 0.6745;
}

/// The standard normal's density at its q-quantile (z_q by bisection on the
/// cdf); 0 outside (0, 1).
double normal_pdf_at_quantile(double q) {
  if (!(q > 0 && q < 1)) return 0.0;
  double lo = -10, hi = 10;
  for (int i = 0; i < 60; ++i) {
    const double z = 0.5 * (lo + hi);
    (0.5 * std::erfc(-z / std::sqrt(2.0)) < q ? lo : hi) = z;
  }
  const double z = 0.5 * (lo + hi);
  return std::exp(-0.5 * z * z) / std::sqrt(2 * M_PI);
}

}  // namespace

BudgetController::BudgetController(const BudgetControllerOptions& options)
    : o_(options),
      quantile_pdf_(normal_pdf_at_quantile(options.quantile)),
      budget_ms_(options.target_ms) {}

void BudgetController::update(double predicted_ms, double measured_ms) {
  if (!(predicted_ms > 0) || !(measured_ms > 0)) return;
  const double r = measured_ms / predicted_ms;
  // One frame far over (or under) its expected ratio is a surprise; the
  // next one too is the machine's new pace (a sustained slowdown must not
  // freeze the loop). A single fast frame would otherwise raise the next
  // budget 2x and make the next frame the slow one.
  const bool far = r > o_.outlier_factor * ratio_ || r * o_.outlier_factor < ratio_;
  surprise_ = !first_ && far && !surprise_;
  if (!first_) {
    residuals_.push_back(std::log(r / ratio_));
    while (int(residuals_.size()) > std::max(1, o_.residual_window)) residuals_.pop_front();
  }
  // The spread: the frame h back, less the median of the 2h + 1 around it.
  const std::size_t h = std::size_t(std::max(1, o_.centre_half_width));
  log_ratios_.push_back(std::log(r));
  while (log_ratios_.size() > 2 * h + 1) log_ratios_.pop_front();
  if (log_ratios_.size() == 2 * h + 1) {
    std::vector<double> w(log_ratios_.begin(), log_ratios_.end());
    std::nth_element(w.begin(), w.begin() + std::ptrdiff_t(h), w.end());
    spread_.push_back(log_ratios_[h] - w[h]);
    while (int(spread_.size()) > std::max(1, o_.quantile_window)) spread_.pop_front();
  }
  if (!surprise_) {
    // Log-domain smoothing: a ratio of 2 and one of 0.5 weigh alike.
    if (!first_) changes_.push_back(std::abs(std::log(r) - last_log_ratio_));
    while (int(changes_.size()) > std::max(1, o_.spread_window)) changes_.pop_front();
    last_log_ratio_ = std::log(r);
    const double w = gain();
    ratio_ = first_ ? r : std::exp((1 - w) * std::log(ratio_) + w * std::log(r));
    first_ = false;
    const double setpoint = setpoint_ms();
    const double error = std::clamp((setpoint - measured_ms) / o_.target_ms, -1.0, 1.0);
    // A frame that left its budget over (every instance at its best) was
    // short for want of anything to draw, not for a loose budget: its error
    // must not raise the integral (see `spent_fraction`).
    const bool spent = predicted_ms >= o_.spent_fraction * budget_ms_;
    if (spent || error < 0)
      integral_ = std::clamp(integral_ + o_.ki * error, -o_.integral_limit, o_.integral_limit);
    const double correction = std::max(0.1, 1.0 + o_.kp * error + integral_);
    budget_ms_ = setpoint / ratio_ * correction;
  }
}

double BudgetController::gain() const {
  if (residuals_.size() < 8 || !(o_.drift > 0)) return o_.ratio_smoothing;
  const double r = std::max(1e-8, std::pow(robust_sigma(residuals_), 2)), q = o_.drift * o_.drift;
  // The steady-state Kalman gain for x' = x + N(0, q) seen as x + N(0, r):
  // the prior variance M solves M^2 = q M + q r, gain M / (M + r).
  const double k = (-q + std::sqrt(q * q + 4 * q * r)) / (2 * r);
  return std::min(o_.ratio_smoothing, k);
}

double BudgetController::noise() const {
  // Nothing measured yet is not no noise: without a prior the first frames
  // of a walkthrough run over target more often
  // (docs/results/2026-12-02-hybrid-budget-margin.md).
  if (int(changes_.size()) < std::max(1, o_.prior_changes)) return o_.prior_noise;
  std::vector<double> c(changes_.begin(), changes_.end());
  std::nth_element(c.begin(), c.begin() + std::ptrdiff_t(c.size() / 2), c.end());
  // |X1 - X2| of two normals has median 0.6745 * sqrt(2) sigma.
  return c[c.size() / 2] / (0.6745 * std::sqrt(2.0));
}

bool BudgetController::tail_ready() const {
  // At least one, so an empty spread is never ready.
  return int(spread_.size()) >= std::max(1, std::min(o_.quantile_min_frames, o_.quantile_window));
}

double BudgetController::tail() const {
  const std::size_t n = spread_.size();
  if (!tail_ready()) return NAN;
  std::vector<double> e(spread_.begin(), spread_.end());
  const std::size_t k =
      std::min(n - 1, std::size_t(std::max(0.0, std::ceil(o_.quantile * double(n)) - 1)));
  std::nth_element(e.begin(), e.begin() + std::ptrdiff_t(k), e.end());
  return e[k];
}

double BudgetController::tail_error() const {
  const double q = o_.quantile;
  if (!tail_ready() || !(quantile_pdf_ > 0)) return 0.0;
  // A normal's sample q-quantile's standard error, sqrt(q (1 - q) / n) /
  // pdf(z_q) sigma, sigma the spread's robust one.
  return std::sqrt(q * (1 - q) / double(spread_.size())) / quantile_pdf_ * robust_sigma(spread_);
}

double BudgetController::setpoint_ms() const {
  // The frames' own tail about their local pace is the spread to cover,
  // with a margin for how little a window's frames say about a 95th percentile.
  const double q = tail();
  auto clamped = [&](double f) { return o_.target_ms * std::clamp(f, o_.min_setpoint, 1.0); };
  if (std::isfinite(q))
    return clamped(o_.tolerance * std::exp(-q - o_.quantile_margin * tail_error()));
  // Too few frames yet: the budget follows the smoothed ratio, which carries
  // w / (2 - w) of the frames' noise variance into the next frame: the
  // spread to cover is the frame's own and the budget's together.
  const double w = gain();
  const double sigma = noise() * std::sqrt(1 + w / (2 - w));
  return clamped(o_.tolerance * std::exp(-o_.z * sigma));
}

void QualityStepController::update(double measured_ms) {
  // The step grows with the miss (one step per 10% of the target, at most
  // `max_steps`): a frame at 3x the target must not wait 40 frames.
  const double miss = std::abs(measured_ms - o_.target_ms) / (0.1 * o_.target_ms);
  const double step = o_.step * std::clamp(std::floor(miss), 1.0, o_.max_steps);
  if (measured_ms > o_.target_ms)
    quality_ -= step;
  else if (measured_ms < 0.9 * o_.target_ms)
    quality_ += o_.step;
  quality_ = std::clamp(quality_, o_.min_quality, o_.max_quality);
}

}  // namespace terrasprite
