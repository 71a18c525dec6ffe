// SPDX-License-Identifier: MIT
// Replays a budget controller on the frames of a recorded walkthrough, so a
// change to the loop can be judged on this machine's real noise without
// flying it again: each recorded frame gives its surprise, measured /
// predicted, the least the selection could have drawn and, where it left
// budget over, the most it wanted; a replayed frame is predicted at its
// budget (within those) and takes the recorded surprise. It assumes the
// surprise does not depend on the budget.
#pragma once
#include <vector>

#include "terrasprite/hybrid/budget_controller.h"

namespace terrasprite {

struct RecordedFrame {
  double ms = 0;            ///< measured frame time, ms (> 0)
  double predicted_ms = 0;  ///< the cost model's prediction for what was drawn (> 0)
  double budget_ms = 0;     ///< the budget the selection was given, ms
};

struct ReplayResult {
  std::vector<double> ms, budget_ms;  ///< per replayed frame
  double p95_ms = 0, median_ms = 0, mean_budget_ms = 0;
};

/// The floor a recorded frame puts under any budget: its prediction where
/// the selection could not get down to its budget (predicted over budget by
/// more than 2%), else 0 (it could have drawn less).
double recorded_floor_ms(const RecordedFrame& f);

/// The most a recorded frame's selection would have spent of any budget: its
/// prediction where it left its budget over (under the default
/// `BudgetControllerOptions::spent_fraction` of it: every instance at its
/// best already, a larger budget buys nothing), else unbounded.
double recorded_demand_ms(const RecordedFrame& f);

/// Runs `options` (target included) over `frames` in order. Frames with a
/// non-positive time or prediction are skipped. Empty input: an empty result.
ReplayResult replay_controller(const std::vector<RecordedFrame>& frames,
                               const BudgetControllerOptions& options);

}  // namespace terrasprite
