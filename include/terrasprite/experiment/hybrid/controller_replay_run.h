// SPDX-License-Identifier: MIT
// The budget controller replayed on the frames of recorded walkthroughs
// (`bench hybrid` output directories: hybrid.json's target_ms and each
// scenario's frames_<scenario>.dat), with its options changed, to judge a
// change to the loop on this machine's real noise in seconds instead of
// flying the walkthrough again (hybrid/controller_replay.h replays one series).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "terrasprite/experiment/hybrid/hybrid.h"
#include "terrasprite/hybrid/controller_replay.h"

namespace terrasprite {

struct ControllerReplayOptions {
  std::vector<std::string> runs;  ///< bench hybrid output directories, at least one
  std::vector<WalkScenario> scenarios{WalkScenario::kPm, WalkScenario::kMixedOptimal};
  BudgetControllerOptions controller;  ///< target_ms is each run's own
};

/// One scenario of one run, recorded and replayed. Ratios are over the run's target.
struct ReplaySeries {
  std::string run;
  WalkScenario scenario = WalkScenario::kPm;
  double target_ms = 0;
  std::size_t frames = 0;  ///< frames replayed
  double recorded_p95_over_target = 0, replayed_p95_over_target = 0;
  double replayed_median_over_target = 0, replayed_budget_over_target = 0;
  /// Per frame, to show where a dip falls (a mean hides it), ms.
  std::vector<double> recorded_budget_ms, replayed_budget_ms;
};

struct ControllerReplayResult {
  BudgetControllerOptions controller;  ///< as replayed (target_ms: the options')
  std::vector<ReplaySeries> series;    ///< by run, then by scenario
  /// Fractions of the series whose p95 is within +10% of the target.
  double recorded_within_10pct = 0, replayed_within_10pct = 0;
  double replayed_p95_median = 0;   ///< median over series of the replayed p95 / target
  double replayed_budget_mean = 0;  ///< mean over series of the replayed budget / target
};

/// The recorded frames of one scenario of one run: ms, predicted_ms and
/// budget_ms by their header names. Throws InputError naming the file
/// (missing, no header, a column missing, a field not a number, a short row).
std::vector<RecordedFrame> read_recorded_frames(const std::string& file);

/// The target_ms of the run in `run_dir` (its hybrid.json). Throws
/// InputError naming the file when it is missing, not JSON or has no
/// positive target_ms.
double recorded_target_ms(const std::string& run_dir);

/// Replays `o.controller` on every run's scenarios. Throws InputError for
/// no runs, or a run or frames file that cannot be read or replayed.
ControllerReplayResult run_controller_replay(const ControllerReplayOptions& o);

}  // namespace terrasprite
