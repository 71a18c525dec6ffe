// SPDX-License-Identifier: MIT
// The controller replay: a run recorded from the loop itself replays to the
// same frames (its floors and its frames with budget left over included),
// and a change of options changes them. No GL, under 10 ms.
#include "terrasprite/hybrid/controller_replay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace terrasprite {
namespace {

/// A walkthrough-like run of the loop: 20% noise, the selection's floor now
/// and then far over the budget (every instance at its cheapest), and 20
/// frames whose scene uses only 40% of the target (every instance at its best).
std::vector<RecordedFrame> recorded_run(const BudgetControllerOptions& o) {
  BudgetController c(o);
  std::mt19937 rng{9};
  std::normal_distribution<double> noise(0, 0.2);
  std::vector<RecordedFrame> frames;
  for (int f = 0; f < 160; ++f) {
    const double budget = c.budget_ms();
    const double floor = f % 40 == 39 ? 2 * o.target_ms : 0.0;
    const double wants = f >= 60 && f < 80 ? 0.4 * o.target_ms : INFINITY;
    const double predicted = std::max(std::min(budget, wants), floor);
    const double ms = predicted * std::exp(noise(rng));
    c.update(predicted, ms);
    frames.push_back({ms, predicted, budget});
  }
  return frames;
}

TEST(ControllerReplay, TheLoopsOwnRunReplaysToTheSameFrames) {
  const BudgetControllerOptions o{.target_ms = 10};
  const std::vector<RecordedFrame> frames = recorded_run(o);
  const ReplayResult r = replay_controller(frames, o);
  ASSERT_EQ(r.ms.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_NEAR(r.ms[i], frames[i].ms, 1e-9 * frames[i].ms) << "frame " << i;
    EXPECT_NEAR(r.budget_ms[i], frames[i].budget_ms, 1e-9 * frames[i].budget_ms) << "frame " << i;
  }
  EXPECT_GT(r.p95_ms, r.median_ms);
}

TEST(ControllerReplay, AnotherAimGivesOtherFramesAndTheFloorStays) {
  const BudgetControllerOptions o{.target_ms = 10};
  const std::vector<RecordedFrame> frames = recorded_run(o);
  BudgetControllerOptions bold = o;
  bold.quantile_margin = 0;
  bold.tolerance = 1.1;
  const ReplayResult a = replay_controller(frames, o), b = replay_controller(frames, bold);
  EXPECT_GT(b.mean_budget_ms, a.mean_budget_ms);
  EXPECT_GT(b.p95_ms, a.p95_ms);
  // Where the recorded selection could not get down to its budget, the
  // replay cannot either.
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (recorded_floor_ms(frames[i]) > 0) {
      EXPECT_GE(b.ms[i] / (frames[i].ms / frames[i].predicted_ms), frames[i].predicted_ms - 1e-9);
    }
  // Where it left budget over, the replay spends no more than it did.
  int left_over = 0;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (std::isfinite(recorded_demand_ms(frames[i]))) {
      ++left_over;
      EXPECT_LE(b.ms[i] / (frames[i].ms / frames[i].predicted_ms), frames[i].predicted_ms + 1e-9);
    }
  EXPECT_EQ(left_over, 19);  // the 20 but frame 79, whose floor is over its budget
  // Frames without a time or a prediction are skipped.
  std::vector<RecordedFrame> holes = frames;
  holes[3].ms = 0;
  holes[7].predicted_ms = NAN;
  EXPECT_EQ(replay_controller(holes, o).ms.size(), frames.size() - 2);
  EXPECT_TRUE(replay_controller({}, o).ms.empty());
}

}  // namespace
}  // namespace terrasprite
