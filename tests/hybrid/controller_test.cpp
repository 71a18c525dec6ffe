// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "terrasprite/hybrid/budget_controller.h"
#include "terrasprite/hybrid/draw_cost_model.h"
#include "terrasprite/hybrid/frame_pace.h"
#include "terrasprite/hybrid/measured_fixed_time.h"

namespace terrasprite {
namespace {

/// A simulated renderer: the selection spends the budget up to what the
/// scene can use (predicted = min(budget, 400 ms)), and the machine takes
/// `load` times the prediction, with 2% noise (log-normal).
struct Simulation {
  double load = 1.0;
  std::mt19937 rng{5};
  double frame(double budget, double& predicted) {
    predicted = std::clamp(budget, 5.0, 400.0);
    return load * predicted * std::exp(std::normal_distribution<double>(0, 0.02)(rng));
  }
};

TEST(BudgetController, StepChangeReturnsWithinTenPercentWithoutOscillating) {
  const double target = 50;
  BudgetController c({.target_ms = target});
  Simulation sim;
  std::vector<double> ms;
  for (int f = 0; f < 120; ++f) {
    if (f == 40) sim.load = 2.0;  // a step: the machine halves its speed
    if (f == 80) sim.load = 0.7;
    double predicted = 0;
    const double measured = sim.frame(c.budget_ms(), predicted);
    c.update(predicted, measured);
    ms.push_back(measured);
  }
  // Settles within 10% of the target in at most 4 frames after each step...
  for (int step : {0, 40, 80}) {
    int settled = -1;
    for (int f = step; f < step + 40; ++f) {
      bool all_in = true;
      for (int g = f; g < step + 40; ++g)
        all_in = all_in && std::abs(ms[g] - target) <= 0.1 * target;
      if (all_in) {
        settled = f - step;
        break;
      }
    }
    EXPECT_NE(settled, -1) << "step at " << step << ": never within 10%";
    EXPECT_LE(settled, 4) << "step at " << step;
    std::printf("step at frame %d: within 10%% from %d frames on\n", step, settled);
    // ...and does not oscillate: after the step's own frame no frame
    // overshoots by more than 15%, and the error changes sign beyond a 5%
    // band at most a few times (noise, not a swing).
    int swings = 0, last_sign = 0;
    for (int f = step + 1; f < step + 40; ++f) {
      EXPECT_LT(ms[f], 1.15 * target) << "frame " << f;
      const double e = (ms[f] - target) / target;
      const int sign = e > 0.05 ? 1 : e < -0.05 ? -1 : 0;
      if (sign && last_sign && sign != last_sign) ++swings;
      if (sign) last_sign = sign;
    }
    EXPECT_LE(swings, 2) << "step at " << step;
  }
}

TEST(BudgetController, NoisyMachineIsHeldByItsP95) {
  // A shared machine: every frame 25% (log-normal sigma) off its prediction.
  // The loop aims the median under the target by the measured noise so that
  // the 95th percentile lands near +10%.
  const double target = 50;
  BudgetController c({.target_ms = target});
  std::mt19937 rng{7};
  std::vector<double> ms;
  for (int f = 0; f < 400; ++f) {
    const double predicted = std::clamp(c.budget_ms(), 5.0, 400.0);
    const double measured = predicted * std::exp(std::normal_distribution<double>(0, 0.25)(rng));
    c.update(predicted, measured);
    if (f >= 20) ms.push_back(measured);
  }
  std::sort(ms.begin(), ms.end());
  const double p95 = ms[std::size_t(std::ceil(0.95 * double(ms.size()))) - 1];
  const double median = ms[ms.size() / 2];
  std::printf("noise 25%%: median %.1f, p95 %.1f (target %.0f), sigma %.3f\n", median, p95, target,
              c.noise());
  EXPECT_NEAR(c.noise(), 0.25, 0.08);
  EXPECT_LT(median, target);
  EXPECT_LT(p95, 1.15 * target);
}

TEST(BudgetController, WalkthroughLengthRunsHoldTheirP95) {
  // The bench's case: 160 frames, the p95 over them against +10%, on a
  // machine like this one: 20% log-normal noise a frame, one stall in 15
  // (1.5x), and a pace that wanders (a random walk, 3% a frame). Aimed at
  // exactly +10%, a 40-frame quantile is low as often as high and a low one
  // costs more than a high one earns: 1 of these 20 runs held +10% (the
  // replayed walkthroughs agree: 3% of 94). The margin holds 19 of them,
  // without starving the frames.
  const double target = 10;
  int held = 0;
  double median_sum = 0;
  const int runs = 20;
  for (int seed = 0; seed < runs; ++seed) {
    BudgetController c({.target_ms = target});
    std::mt19937 rng(std::uint32_t(100 + seed));
    std::normal_distribution<double> noise(0, 0.2), walk(0, 0.03);
    std::uniform_real_distribution<double> u(0, 1);
    double pace = 0;
    std::vector<double> ms;
    for (int f = 0; f < 160; ++f) {
      pace = std::clamp(pace + walk(rng), -0.5, 0.5);
      const double predicted = std::clamp(c.budget_ms(), 1.0, 100.0);
      const double stall = u(rng) < 1.0 / 15 ? 1.5 : 1.0;
      const double measured = stall * predicted * std::exp(pace + noise(rng));
      c.update(predicted, measured);
      ms.push_back(measured);
    }
    std::sort(ms.begin(), ms.end());
    held += ms[std::size_t(std::ceil(0.95 * double(ms.size()))) - 1] <= 1.1 * target;
    median_sum += ms[ms.size() / 2];
  }
  std::printf(
      "walkthrough-length runs: %d of %d held p95 <= +10%%, mean median %.2f (target %.0f)\n", held,
      runs, median_sum / runs, target);
  EXPECT_GE(held, 17);
  EXPECT_GT(median_sum / runs, 0.55 * target);
}

TEST(BudgetController, HeavyTailedFramesAreHeldByTheirP95) {
  // A walkthrough's frames: 5% noise, and one frame in twelve 1.6x slow (a
  // stall the cost model cannot see, under the surprise factor). The
  // median change says sigma about 0.1; the tail is what the p95 sees.
  const double target = 10;
  BudgetController c({.target_ms = target});
  std::mt19937 rng{11};
  std::vector<double> ms;
  for (int f = 0; f < 600; ++f) {
    const double predicted = std::clamp(c.budget_ms(), 1.0, 100.0);
    const double slow = std::uniform_real_distribution<double>(0, 1)(rng) < 1.0 / 12 ? 1.6 : 1.0;
    const double measured =
        slow * predicted * std::exp(std::normal_distribution<double>(0, 0.05)(rng));
    c.update(predicted, measured);
    if (f >= 40) ms.push_back(measured);
  }
  std::sort(ms.begin(), ms.end());
  const double p95 = ms[std::size_t(std::ceil(0.95 * double(ms.size()))) - 1];
  std::printf("heavy tail: median %.2f, p95 %.2f (target %.0f), sigma %.3f, tail %.3f\n",
              ms[ms.size() / 2], p95, target, c.noise(), c.tail());
  // sigma (0.11 here) would aim the median at 8.8 and the p95 at +40%.
  EXPECT_LT(p95, 1.2 * target);
  EXPECT_GT(p95, 0.9 * target);  // without starving the frame
}

TEST(BudgetController, ABuildBesideItDoesNotStarveTheFrames) {
  // One frame in ten 4x slow (a compiler on the same cores): no selection
  // holds that p95, so the setpoint stops at half the target.
  BudgetController c({.target_ms = 10});
  for (int f = 0; f < 100; ++f) {
    const double predicted = std::clamp(c.budget_ms(), 1.0, 100.0);
    c.update(predicted, (f % 10 == 3 ? 4.0 : 1.0) * predicted);
  }
  EXPECT_GT(c.tail(), std::log(3.0));
  EXPECT_NEAR(c.setpoint_ms(), 5.0, 1e-9);
}

TEST(BudgetController, TheTailWaitsForFramesEnoughForAQuantile) {
  // A 95th percentile of 10 frames is their largest, and its margin is wide:
  // the loop aims by sigma until `quantile_min_frames` spreads are in (each
  // known `centre_half_width` frames late, after the first 2h + 1).
  BudgetControllerOptions o{.target_ms = 10};
  BudgetController c(o);
  std::mt19937 rng{3};
  const int h = o.centre_half_width, first = 2 * h + 1;
  for (int f = 1; f <= first - 1 + o.quantile_min_frames; ++f) {
    const double predicted = std::clamp(c.budget_ms(), 1.0, 100.0);
    c.update(predicted, predicted * std::exp(std::normal_distribution<double>(0, 0.1)(rng)));
    const int spreads = f - first + 1;
    if (spreads < o.quantile_min_frames)
      EXPECT_TRUE(std::isnan(c.tail())) << f;
    else
      EXPECT_TRUE(std::isfinite(c.tail())) << f;
  }
}

TEST(BudgetController, OneBurstDoesNotHoldTheBudgetDownForAWindow) {
  // This machine: a burst of three frames 1.4x their prediction (not one-off
  // surprises), some 25 frames before a checkpoint. Three of 40 frames made
  // a 40-frame window's 95th percentile, and the budget stayed at 0.7 of
  // the target to the checkpoint; three of 160 are under 5%.
  auto budget_after_burst = [](int window) {
    BudgetController c({.target_ms = 20, .quantile_window = window});
    std::mt19937 rng{9};
    double before = 0;
    for (int f = 0; f < 230; ++f) {
      const double predicted = std::clamp(c.budget_ms(), 1.0, 100.0);
      const double burst = f >= 200 && f < 203 ? 1.4 : 1.0;
      c.update(predicted,
               burst * predicted * std::exp(std::normal_distribution<double>(0, 0.05)(rng)));
      if (f == 199) before = c.budget_ms();
    }
    return c.budget_ms() / before;  // 27 frames after the burst
  };
  const double long_window = budget_after_burst(BudgetControllerOptions{}.quantile_window);
  const double short_window = budget_after_burst(40);
  std::printf("budget 27 frames after a burst / before it: window 40 %.3f, default %.3f\n",
              short_window, long_window);
  EXPECT_LT(short_window, 0.9);  // the case the default is for (0.85 here)
  EXPECT_GT(long_window, 0.95);  // (1.0 here)
}

TEST(BudgetController, NoisyFramesDoNotSwingTheBudget) {
  // 25% noise (log-normal), nothing to follow: the ratio's weight falls to
  // about 0.2 and the budget moves half as much frame to frame as with a
  // fixed 0.6, with the 95th percentile of the frames no higher.
  auto run = [](double drift, double& budget_change, double& p95) {
    BudgetController c({.target_ms = 10, .drift = drift});
    std::mt19937 rng{3};
    std::vector<double> changes, ms;
    double last = c.budget_ms();
    for (int f = 0; f < 600; ++f) {
      const double predicted = std::clamp(c.budget_ms(), 1.0, 100.0);
      const double measured = predicted * std::exp(std::normal_distribution<double>(0, 0.25)(rng));
      c.update(predicted, measured);
      if (f < 40) continue;
      changes.push_back(std::abs(std::log(c.budget_ms() / last)));
      ms.push_back(measured);
      last = c.budget_ms();
    }
    std::sort(changes.begin(), changes.end());
    std::sort(ms.begin(), ms.end());
    budget_change = changes[changes.size() / 2];
    p95 = ms[std::size_t(0.95 * double(ms.size()))];
    return c.gain();
  };
  double fixed_change = 0, fixed_p95 = 0, kalman_change = 0, kalman_p95 = 0;
  EXPECT_DOUBLE_EQ(run(0, fixed_change, fixed_p95), 0.6);
  const double gain = run(0.05, kalman_change, kalman_p95);
  std::printf("25%% noise: gain %.2f; budget change %.3f (fixed 0.6: %.3f), p95 %.2f (%.2f)\n",
              gain, kalman_change, fixed_change, kalman_p95, fixed_p95);
  EXPECT_GT(gain, 0.1);
  EXPECT_LT(gain, 0.3);
  EXPECT_LT(kalman_change, 0.6 * fixed_change);
  EXPECT_LT(kalman_p95, 1.05 * fixed_p95);
}

TEST(BudgetController, FramesWithNothingMoreToDrawDoNotWindTheBudgetUp) {
  // 30 frames whose scene can use only 40% of the budget (every instance at
  // its best), then the full load again (the walkthrough's D: objects behind
  // the hill, then in view). Their short times must not wind the budget up
  // for the frames after; with every frame integrated (spent_fraction 0, the
  // loop before) they do, and the first full frames run far over.
  const double target = 20;
  auto worst_after = [&](double spent_fraction, double& peak_budget) {
    BudgetController c({.target_ms = target, .spent_fraction = spent_fraction});
    std::mt19937 rng{7};
    double worst = 0;
    for (int f = 0; f < 100; ++f) {
      const double wants = f >= 30 && f < 60 ? 0.4 * target : 1e9;  // predicted ms it can use
      const double predicted = std::min(c.budget_ms(), wants);
      const double measured = predicted * std::exp(std::normal_distribution<double>(0, 0.03)(rng));
      if (f >= 60 && f < 70) worst = std::max(worst, measured);
      if (f < 60) peak_budget = std::max(peak_budget, c.budget_ms());
      c.update(predicted, measured);
    }
    return worst;
  };
  double peak = 0, peak_before = 0;
  const double now = worst_after(BudgetControllerOptions{}.spent_fraction, peak);
  const double before = worst_after(0.0, peak_before);
  std::printf(
      "after 30 frames with nothing to draw: worst %.1f ms, budget peak %.1f ms "
      "(integrating them: %.1f, %.1f) at %.0f ms\n",
      now, peak, before, peak_before, target);
  EXPECT_LE(now, 1.1 * target);
  EXPECT_LE(peak, 1.2 * target);
  EXPECT_GT(before, 1.3 * target);  // the windup this guards against
}

TEST(BudgetController, OneSurpriseFrameDoesNotThrowTheRestOff) {
  // A twin fed the same frames without the surprises: the loop may still be
  // settling (the first frames assume noise), so the check is "as if the
  // surprise had not happened", not "unchanged".
  BudgetController c({.target_ms = 50}), twin({.target_ms = 50});
  for (int f = 0; f < 20; ++f) {
    c.update(c.budget_ms(), c.budget_ms());
    twin.update(twin.budget_ms(), twin.budget_ms());
  }
  const double before = c.budget_ms();
  c.update(before, 10 * before);  // a keyframe, an impostor build
  EXPECT_NEAR(c.budget_ms(), twin.budget_ms(), 1e-9);
  EXPECT_TRUE(c.last_was_surprise());
  c.update(before, before);
  twin.update(before, before);
  c.update(before, 0.1 * before);  // a glitch the other way
  EXPECT_NEAR(c.budget_ms(), twin.budget_ms(), 1e-9);
  c.update(before, before);
  // Two slow frames in a row are the machine's new pace: the budget follows.
  c.update(before, 10 * before);
  c.update(before, 10 * before);
  EXPECT_FALSE(c.last_was_surprise());
  EXPECT_LT(c.budget_ms(), 0.5 * before);
}

TEST(QualityStepController, RaisesUnderAndLowersOverTarget) {
  QualityStepController q({.target_ms = 50, .step = 0.01, .start_quality = 0.9});
  q.update(52);  // just over: one step
  EXPECT_NEAR(q.quality(), 0.89, 1e-12);
  q.update(80);  // 60% over: six steps
  EXPECT_NEAR(q.quality(), 0.83, 1e-12);
  q.update(20);  // under: one step up
  q.update(20);
  EXPECT_NEAR(q.quality(), 0.85, 1e-12);
}

TEST(DrawCostModel, FitsMeasuredDrawsAndRefitsOnline) {
  // Truth: 0.01 ms per instance, 2e-5 ms per triangle, 1e-5 ms per pixel.
  std::vector<DrawSample> draws;
  for (double n : {1.0, 4.0, 16.0})
    for (double tris : {1000.0, 10000.0})
      for (double px : {500.0, 5000.0})
        draws.push_back({1, n, n * tris, n * px, n * (0.01 + 2e-5 * tris + 1e-5 * px)});
  DrawCostModel m;
  m.calibrate(ObjectKind::kMesh, draws, 0.25);
  EXPECT_NEAR(m.terms(ObjectKind::kMesh).per_draw_ms, 0.0025, 1e-9);
  EXPECT_NEAR(m.terms(ObjectKind::kMesh).per_instance_ms, 0.0075, 1e-9);
  EXPECT_NEAR(m.terms(ObjectKind::kMesh).per_triangle_ms, 2e-5, 1e-12);
  EXPECT_NEAR(m.terms(ObjectKind::kMesh).per_pixel_ms, 1e-5, 1e-12);
  m.set_frame_ms(20);
  // The machine becomes 1.5x slower: frame predictions follow.
  FrameLoad load;
  load.kinds[0] = {1, 100, 1e6, 2e5, 0};
  const double before = m.predict(load);
  for (int f = 0; f < 40; ++f) {
    load.kinds[0].triangles = 1e6 * (1 + 0.3 * (f % 3));
    m.observe(load, 1.5 * (20 + 100 * 0.01 + 2e-5 * load.kinds[0].triangles + 1e-5 * 2e5));
  }
  load.kinds[0].triangles = 1e6;
  EXPECT_NEAR(m.predict(load) / (1.5 * before), 1.0, 0.05);
}

TEST(DrawCostModel, LearnsWhatAnImpostorCostsInAFrame) {
  // Calibrated: relief 0.02 ms + 1e-5 ms a pixel, meshes 2e-5 ms a
  // triangle. In the frames each relief costs 0.12 ms more, however many
  // are drawn (0-12, varying); meshes and the frame term are as calibrated.
  // Noise-free, it is learnt in 400 frames (in 60 with the refit's former
  // settings, which trusted one frame more and forgot sooner; see
  // NoisyFramesDoNotTradeTheMeshesForTheFrameTerm for their price).
  DrawCostModel m;
  m.set_terms(ObjectKind::kMesh, {0, 0, 2e-5, 0});
  const Representation relief{ObjectKind::kRelief, 0, 64}, octa{ObjectKind::kOctahedral, 0, 64};
  m.set_cost(relief, {0.02, 1e-5});
  m.set_cost(octa, {0.01, 1e-5});
  m.set_frame_ms(2);
  EXPECT_EQ(m.impostor_extra_ms(ObjectKind::kRelief), 0.0);  // prior: as calibrated
  EXPECT_NEAR(m.instance_ms(relief, 12, 400), 0.024, 1e-12);
  for (int f = 0; f < 400; ++f) {
    FrameLoad load;
    load.kinds[0] = {1, 50, 2e5 * (1 + 0.2 * (f % 4)), 0, 0};
    const int reliefs = (f * 7) % 13;
    for (int i = 0; i < reliefs; ++i) m.add(load, relief, 12, 400);
    const double truth = 2 + 2e-5 * load.kinds[0].triangles + reliefs * (0.024 + 0.12);
    m.observe(load, truth);
  }
  EXPECT_NEAR(m.impostor_extra_ms(ObjectKind::kRelief), 0.12, 0.02);
  EXPECT_NEAR(m.instance_ms(relief, 12, 400), 0.144, 0.02);
  // The kinds' parts and the frame term make up the prediction.
  {
    FrameLoad load;
    load.kinds[0] = {1, 50, 2e5, 0, 0};
    for (int i = 0; i < 5; ++i) m.add(load, relief, 12, 400);
    EXPECT_NEAR(m.kind_ms(load, ObjectKind::kRelief), 5 * m.instance_ms(relief, 12, 400), 1e-9);
    EXPECT_EQ(m.kind_ms(load, ObjectKind::kOctahedral), 0.0);
    EXPECT_NEAR(
        m.frame_ms() + m.kind_ms(load, ObjectKind::kMesh) + m.kind_ms(load, ObjectKind::kRelief),
        m.predict(load), 1e-9);
  }
  // Never drawn, the octahedral's extra stays at its prior; meshes have none.
  EXPECT_EQ(m.impostor_extra_ms(ObjectKind::kOctahedral), 0.0);
  EXPECT_EQ(m.impostor_extra_ms(ObjectKind::kMesh), 0.0);
  // Turned off, nothing is learnt.
  DrawCostModel off({.impostor_extra_prior_ms = 0});
  off.set_cost(relief, {0.02, 1e-5});
  off.set_frame_ms(2);
  FrameLoad load;
  for (int i = 0; i < 10; ++i) off.add(load, relief, 12, 400);
  for (int f = 0; f < 20; ++f) off.observe(load, 2 + 10 * 0.144);
  EXPECT_EQ(off.impostor_extra_ms(ObjectKind::kRelief), 0.0);
}

TEST(DrawCostModel, ATermNoFrameDrawsStaysAsItWas) {
  // 20 frames draw octahedral impostors with the meshes, all as calibrated;
  // then 150 frames draw meshes only, on a machine 1.4x slower. The meshes'
  // and the frame's terms follow; the octahedral ones have no part in those
  // frames and stay (before, their covariance with the meshes dragged them
  // along, and in the walkthrough that priced octahedral impostors out).
  DrawCostModel m;
  m.set_terms(ObjectKind::kMesh, {0, 0, 2e-5, 0});
  const Representation octa{ObjectKind::kOctahedral, 0, 64};
  m.set_cost(octa, {0.01, 1e-5});
  m.set_frame_ms(2);
  auto meshes = [](int f) {
    FrameLoad load;
    load.kinds[0] = {1, 50, 2e5 * (1 + 0.2 * (f % 4)), 0, 0};
    return load;
  };
  for (int f = 0; f < 20; ++f) {
    FrameLoad load = meshes(f);
    const int n = 5 + (f * 7) % 11;
    for (int i = 0; i < n; ++i) m.add(load, octa, 2, 400);
    m.observe(load, 2 + 2e-5 * load.kinds[0].triangles + n * 0.014);
  }
  const double extra = m.impostor_extra_ms(ObjectKind::kOctahedral);
  const double cost = m.instance_ms(octa, 2, 400);
  for (int f = 0; f < 150; ++f) {
    const FrameLoad load = meshes(f);
    m.observe(load, 1.4 * (2 + 2e-5 * load.kinds[0].triangles));
  }
  EXPECT_EQ(m.impostor_extra_ms(ObjectKind::kOctahedral), extra);
  EXPECT_EQ(m.instance_ms(octa, 2, 400), cost);
  EXPECT_NEAR(m.predict(meshes(0)) / (1.4 * (2 + 4)), 1.0, 0.05);
}

TEST(DrawCostModel, KnownExtraTimeIsAddedAndNotRefit) {
  // The terrain usually takes 3 ms, the model's frame term; from frame to
  // frame it deviates by -1 to +5 ms, known before the selection. Meshes
  // take 4 ms. With the deviation given, the prediction follows each frame
  // and the frame term stays 3 ms; without it, it cannot.
  auto run = [](bool known, double& frame_term) {
    DrawCostModel m;
    m.set_terms(ObjectKind::kMesh, {0, 0, 2e-5, 0});
    m.set_frame_ms(3);
    double worst = 0;
    for (int f = 0; f < 80; ++f) {
      const double deviation = -1 + 6 * double((f * 5) % 11) / 10;
      FrameLoad load;
      load.kinds[0] = {1, 50, 2e5, 0, 0};
      if (known) load.known_extra_ms = deviation;
      const double truth = 3 + deviation + 4;
      if (f >= 60) worst = std::max(worst, std::abs(m.predict(load) / truth - 1));
      m.observe(load, truth);
    }
    frame_term = m.frame_ms();
    return worst;
  };
  double frame_term = 0;
  EXPECT_LT(run(true, frame_term), 1e-6);
  EXPECT_NEAR(frame_term, 3.0, 1e-6);
  EXPECT_GT(run(false, frame_term), 0.2);
  // Added as it is, before and after a refit.
  DrawCostModel m;
  m.set_frame_ms(3);
  FrameLoad load;
  load.known_extra_ms = 2;
  EXPECT_EQ(m.frame_ms(load), 5.0);
  EXPECT_EQ(m.predict(load), 5.0);
  for (int f = 0; f < 10; ++f) m.observe(load, 5.0);
  EXPECT_NEAR(m.frame_ms(), 3.0, 1e-9);
}

// Frames as the walkthrough's: the frame term (5 ms) beside a few meshes
// (3 ms, varying +-40%), then, over the last 20 frames, many (9 ms); frame
// times 22% noisy (log-normal), one 2.1x frame near the end. Everything
// costs as calibrated, so the meshes' multiplier should stay near 1. With
// the refit's former settings (forgetting 0.95, noise 0.15, no spread drawn
// in) it fell to its floor (0.05) in some of 40 seeds: the policy then
// priced every mesh at a twentieth (in a walkthrough, 177 instances at full
// geometry: 138 ms against an 18 ms target).
TEST(DrawCostModel, NoisyFramesDoNotTradeTheMeshesForTheFrameTerm) {
  auto lowest = [](const CostModelOptions& o, int seed) {
    DrawCostModel m(o);
    m.set_terms(ObjectKind::kMesh, {0.005, 0.001, 2.7e-4, 3.3e-6});
    m.set_frame_ms(5);
    std::mt19937 rng{std::uint32_t(seed)};
    std::normal_distribution<double> noise(0, 0.22);
    std::uniform_real_distribution<double> vary(0.6, 1.4);
    double low = INFINITY;
    for (int f = 0; f < 160; ++f) {
      const double many = std::clamp((f - 140) / 16.0, 0.0, 1.0);
      FrameLoad load;
      load.kinds[0].draws = (8 + 20 * many) * vary(rng);
      load.kinds[0].instances = 14 + 100 * many;
      load.fixed_ms[0] = (3 + 6 * many) * vary(rng);
      load.pixel_ms[0] = (1.5 - many) * vary(rng);
      const double truth = 5 + 0.005 * load.kinds[0].draws + load.fixed_ms[0] + load.pixel_ms[0];
      m.observe(load, truth * std::exp(noise(rng)) * (f == 157 ? 2.1 : 1.0));
      FrameLoad probe;  // the meshes' instances alone: their multiplier
      probe.kinds[0].instances = 1;
      probe.fixed_ms[0] = 1;
      low = std::min(low, m.kind_ms(probe, ObjectKind::kMesh));
    }
    return low;
  };
  const CostModelOptions former{.forgetting = 0.95, .noise_fraction = 0.15, .spread_retention = 1};
  int floored = 0;
  double worst = INFINITY;
  for (int seed = 1; seed <= 40; ++seed) {
    floored += lowest(former, seed) < 0.1;
    worst = std::min(worst, lowest(CostModelOptions{}, seed));
  }
  EXPECT_GE(floored, 3);
  EXPECT_GT(worst, 0.4);
}

TEST(MeasuredFixedTime, DeviationFromTheMedianIsCapped) {
  MeasuredFixedTime f(15, 0.5);
  for (int i = 0; i < 15; ++i) f.deviation(3.0 + 0.1 * (i % 3));
  // One stall counts for half the median (3.1 ms) only; a fast frame too.
  EXPECT_NEAR(f.deviation(8.0), 1.55, 1e-12);
  EXPECT_NEAR(f.deviation(1.0), -1.55, 1e-12);
  // A lasting change to 6 ms is the usual once it is most of the window.
  double last = 1;
  for (int i = 0; i < 9; ++i) last = f.deviation(6.0);
  EXPECT_EQ(last, 0.0);
  EXPECT_NEAR(f.deviation(6.5), 0.5, 1e-12);
  // Nothing measured records nothing.
  EXPECT_EQ(f.deviation(0.0), 0.0);
  EXPECT_EQ(f.deviation(NAN), 0.0);
  f.reset();
  EXPECT_EQ(f.deviation(20.0), 0.0);
  EXPECT_EQ(f.last_log_ratio(), 0.0);
  // The log ratio is the clamped deviation's: a stall reads log 1.5.
  for (int i = 0; i < 14; ++i) f.deviation(20.0);
  f.deviation(100.0);
  EXPECT_NEAR(f.last_log_ratio(), std::log(1.5), 1e-12);
}

TEST(FramePace, LearnsTheSlopeOfTheFrameOnTheReadBacksPace) {
  // The frame runs at the read-back's pace to the power 0.4, plus an
  // offset the refit owns (not the pace's) and noise of its own.
  FramePace p;
  EXPECT_EQ(p.slope(), 0.0);
  EXPECT_EQ(p.factor(0.3), 1.0);
  std::mt19937 rng(3);
  std::normal_distribution<double> z(0.0, 0.3), noise(0.0, 0.05);
  for (int f = 0; f < 7; ++f) p.observe(z(rng), 0.1);
  EXPECT_EQ(p.slope(), 0.0);  // too few frames
  for (int f = 0; f < 200; ++f) {
    const double zf = z(rng);
    p.observe(zf, 0.1 + 0.4 * zf + noise(rng));
  }
  // Shrunk towards 0 by the prior (20 frames of 0.1 against 60 of 0.3).
  EXPECT_NEAR(p.slope(), 0.4 * 60 * 0.09 / (60 * 0.09 + 0.2), 0.05);
  EXPECT_NEAR(p.factor(0.5), std::exp(p.slope() * 0.5), 1e-12);
  // Nothing to learn (the frame ignores the pace): back to 0 within a window.
  for (int f = 0; f < 60; ++f) p.observe(z(rng), noise(rng));
  EXPECT_LT(p.slope(), 0.08);
  // Never negative, never past max_slope; non-finite input ignored.
  for (int f = 0; f < 60; ++f) {
    const double zf = z(rng);
    p.observe(zf, -2 * zf);
  }
  EXPECT_EQ(p.slope(), 0.0);
  for (int f = 0; f < 60; ++f) {
    const double zf = z(rng);
    p.observe(zf, 5 * zf);
  }
  EXPECT_EQ(p.slope(), 1.0);
  p.observe(NAN, 1.0);
  p.observe(0.1, INFINITY);
  EXPECT_EQ(p.slope(), 1.0);
  p.reset();
  EXPECT_EQ(p.slope(), 0.0);
}

}  // namespace
}  // namespace terrasprite
