// SPDX-License-Identifier: MIT
// Holds a target frame time: the selection spends a budget of *predicted*
// milliseconds; this loop sets that budget from the cost model's prediction
// corrected by the measured frame time (a PI loop on the budget), and keeps
// one surprising frame (a keyframe, an impostor build) from throwing it off.
#pragma once

namespace terrasprite {

struct BudgetControllerOptions {
  double target_ms = 100;
  double kp = 0.1;   ///< proportional gain on the relative error (target - measured) / target
  double ki = 0.05;  ///< integral gain (per frame)
  /// measured / predicted is smoothed with this weight for the newest frame.
  double ratio_smoothing = 0.6;
  /// A frame measured over this many times its prediction is a one-off
  /// surprise: it neither moves the ratio nor the integral.
  double outlier_factor = 2.5;
  double integral_limit = 0.5;  ///< anti-windup, relative
};

class BudgetController {
 public:
  explicit BudgetController(const BudgetControllerOptions& options);
  /// The predicted-time budget for the next frame's selection (whole frame,
  /// terrain included), ms.
  double budget_ms() const { return budget_ms_; }
  /// Feeds back one frame: what the cost model predicted for the chosen
  /// representations and what the frame took.
  void update(double predicted_ms, double measured_ms);
  double ratio() const { return ratio_; }

 private:
  BudgetControllerOptions o_;
  double ratio_ = 1.0;  ///< smoothed measured / predicted
  double integral_ = 0;
  double budget_ms_;
  bool first_ = true;
};

/// The paper's controller: raise the target quality while frames come in
/// under the target time, lower it while they are over (Jehaes et al.,
/// section 3.3), by a fixed step within [min, max].
struct QualityStepOptions {
  double target_ms = 100;
  double step = 0.005;
  double min_quality = 0.80, max_quality = 0.995;
  double start_quality = 0.95;
};

class QualityStepController {
 public:
  explicit QualityStepController(const QualityStepOptions& options)
      : o_(options), quality_(options.start_quality) {}
  double quality() const { return quality_; }
  void update(double measured_ms);

 private:
  QualityStepOptions o_;
  double quality_;
};

}  // namespace terrasprite
