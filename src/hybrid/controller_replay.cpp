// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/controller_replay.h"

#include <algorithm>
#include <cmath>

#include "terrasprite/common/stats.h"

namespace terrasprite {

double recorded_floor_ms(const RecordedFrame& f) {
  return f.predicted_ms > 1.02 * f.budget_ms ? f.predicted_ms : 0.0;
}

double recorded_demand_ms(const RecordedFrame& f) {
  // "Left its budget over" as the loop's own anti-windup reads it, at its
  // default: what a recorded frame wanted does not depend on the loop replayed.
  const double spent = BudgetControllerOptions{}.spent_fraction;
  return f.predicted_ms < spent * f.budget_ms ? f.predicted_ms : INFINITY;
}

ReplayResult replay_controller(const std::vector<RecordedFrame>& frames,
                               const BudgetControllerOptions& options) {
  ReplayResult out;
  BudgetController c(options);
  for (const RecordedFrame& f : frames) {
    if (!(f.ms > 0) || !(f.predicted_ms > 0)) continue;
    const double budget = c.budget_ms();
    const double predicted =
        std::max(std::min(budget, recorded_demand_ms(f)), recorded_floor_ms(f));
    const double ms = predicted * (f.ms / f.predicted_ms);
    c.update(predicted, ms);
    out.ms.push_back(ms);
    out.budget_ms.push_back(budget);
  }
  const Summary ms = summarize(out.ms);  // the bench's own p95 (nearest rank)
  out.p95_ms = ms.p95;
  out.median_ms = ms.median;
  out.mean_budget_ms = mean(out.budget_ms);
  return out;
}

}  // namespace terrasprite
