// SPDX-License-Identifier: MIT
// Holds a target frame time: the selection spends a budget of *predicted*
// milliseconds; this loop sets that budget from the cost model's prediction
// corrected by the measured frame time (a PI loop on the budget), and keeps
// one surprising frame (a keyframe, an impostor build) from throwing it off.
// The defaults' figures: docs/results/2026-12-07-hybrid-defaults.md
#pragma once
#include <deque>

namespace terrasprite {

struct BudgetControllerOptions {
  double target_ms = 100;
  double kp = 0.1;   ///< proportional gain on the relative error (target - measured) / target
  double ki = 0.05;  ///< integral gain (per frame)
  /// measured / predicted is smoothed with at most this weight for the
  /// newest frame (see `drift`).
  double ratio_smoothing = 0.6;
  /// How far the true measured / predicted ratio moves per frame (log
  /// domain, standard deviation): the weight of the newest frame is the
  /// steady-state gain of a Kalman filter following such a random walk
  /// through the frames' own noise (the robust spread of the residuals
  /// below, once 8 are in), capped at `ratio_smoothing`. Quiet frames
  /// follow a step in load within a few frames; noisy ones get a small
  /// weight, so that one fast frame does not raise the next budget.
  double drift = 0.05;
  /// A frame whose measured/predicted ratio is this many times over (or
  /// under) the smoothed one is a one-off surprise: it neither moves the
  /// ratio nor the integral. Only one frame in a row: the second such frame
  /// is taken as the machine's pace.
  double outlier_factor = 2.5;
  double integral_limit = 0.5;  ///< anti-windup, relative
  /// Anti-windup for frames with nothing more to draw: a frame predicted
  /// under this fraction of its budget (its selection left the rest over)
  /// does not raise the integral, which would otherwise grow the budget
  /// past what the next full frames can be drawn in.
  double spent_fraction = 0.9;
  /// Until `quantile` (below) takes over, the loop aims the median frame
  /// below the target by the frame-to-frame noise of measured/predicted
  /// (sigma, log domain) so that the z-quantile lands at `tolerance` x
  /// target: setpoint = target x min(1, tolerance x exp(-z sigma')), sigma'
  /// = sigma with the budget's own noise added. sigma is robust: the median
  /// absolute change of log(measured/predicted) between successive frames
  /// over the last `spread_window` frames, / 0.954 (a normal's), so a step
  /// in load (one large change) is not noise.
  double z = 1.645;  ///< one-sided 95%
  double tolerance = 1.05;
  int spread_window = 15;
  /// Until `prior_changes` successive changes are in, sigma is taken as
  /// `prior_noise`, so the first frames keep a margin too.
  double prior_noise = 0.25;
  int prior_changes = 3;
  /// Once `quantile_min_frames` spreads are in, the setpoint comes from the
  /// frames themselves instead of sigma: setpoint = target x min(1,
  /// tolerance x exp(-(q + quantile_margin x se))), q the `quantile` of the
  /// frames' spread over the last `quantile_window` frames (surprises
  /// included: they are the tail), se that sample quantile's standard error
  /// (from the spread's robust sigma). A walkthrough's frame times are not
  /// log-normal: their tail is heavier than the median change says.
  ///
  /// The spread is each frame's log(measured / predicted) less the median of
  /// the `2 centre_half_width + 1` frames around it (known that many frames
  /// late), so a step in the machine's pace is followed by the ratio and not
  /// taken as spread for a window. The margin is there because a sample
  /// quantile is a noisy estimate and a low one costs more than a high one
  /// earns.
  double quantile = 0.95;
  /// Frames in the tail's window. Long enough that a few slow frames in a
  /// row stay under 1 - `quantile` of it (a short window would hold the
  /// budget down for as long as they are in it).
  int quantile_window = 160;
  /// The tail takes over from sigma once this many spread values are in
  /// (at most `quantile_window`): a q-quantile wants 2 / (1 - q) samples,
  /// two of them in the tail; fewer make it the window's largest value.
  int quantile_min_frames = 40;
  /// Frames whose residuals give the ratio's noise (see `drift`).
  int residual_window = 40;
  int centre_half_width = 3;     ///< at least 1 (0 is taken as 1)
  double quantile_margin = 2.0;  ///< standard errors of the sample quantile
  /// Neither setpoint goes under this fraction of the target: where frames
  /// often run several times their expected time (a machine shared with
  /// builds) no selection holds the p95, and aiming for it starves every frame.
  double min_setpoint = 0.5;
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
  /// The weight the next frame's ratio gets in the smoothing (see `drift`).
  double gain() const;
  /// Whether the last frame was set aside as a one-off surprise.
  bool last_was_surprise() const { return surprise_; }
  /// The frame time the loop currently aims at (see `z`), ms.
  double setpoint_ms() const;
  /// The measured noise sigma (log domain; see `spread_window`), or
  /// `prior_noise` while too few frames are in.
  double noise() const;
  /// The `quantile` of the frames' spread (see `centre_half_width`) over
  /// the window, or NaN while fewer than `quantile_min_frames` frames are in.
  double tail() const;
  /// The standard error of `tail()` (log domain; 0 while it is NaN).
  double tail_error() const;

 private:
  /// Whether enough spread is in for the tail (`quantile_min_frames`).
  bool tail_ready() const;

  BudgetControllerOptions o_;
  double quantile_pdf_;  ///< the normal's density at its `quantile` (fixed by the options)
  double ratio_ = 1.0;   ///< smoothed measured / predicted
  double integral_ = 0;
  double last_log_ratio_ = 0;
  std::deque<double> changes_;     ///< |successive change of log ratio|, newest last
  std::deque<double> residuals_;   ///< log(measured / (ratio_ x predicted)), newest last
  std::deque<double> log_ratios_;  ///< log(measured / predicted), the last 2h + 1 frames
  std::deque<double> spread_;      ///< log ratio less its centred median, newest last
  double budget_ms_;
  bool first_ = true;
  bool surprise_ = false;
};

/// The paper's controller: raise the target quality while frames come in
/// under the target time, lower it while they are over (Jehaes et al.,
/// section 3.3), by a fixed step within [min, max].
struct QualityStepOptions {
  double target_ms = 100;
  double step = 0.005;
  /// Over the target, the step is taken once per 10% of the target missed,
  /// up to this many times (1: the paper's fixed step). Raising stays one step.
  double max_steps = 10;
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
