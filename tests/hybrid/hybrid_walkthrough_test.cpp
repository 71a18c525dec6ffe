// SPDX-License-Identifier: MIT
// run_hybrid in-process on the reduced walkthrough (two small models, 12
// instances, 10 frames at 160 x 90, coarse tables measured without a
// cache): the typed result's shape and the invariants of its figures, its
// report's files, and the controller replayed on them. No time is asserted.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "terrasprite/experiment/hybrid/controller_replay_run.h"
#include "terrasprite/experiment/hybrid/hybrid.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/report/hybrid_report.h"
#include "terrasprite/report/json_writer.h"
#include "hybrid_test_util.h"
#include "test_util.h"

namespace {
using namespace terrasprite;

HybridBenchOptions reduced_options(const tstest::TempDir& dir) {
  HybridBenchOptions o;
  o.scene_file = dir / "scene.json";
  o.cache_dir = dir / "cache";
  o.width = 160;
  o.height = 90;
  o.frames = 10;
  o.score_every = 2;
  o.target_ms = 40;
  o.table_sizes = {64};
  o.table_angle_step = 120;
  o.table_headings = {0, 180};
  o.relief_resolutions = {16, 32};
  o.octahedral_resolutions = {16};
  return o;
}

TEST(HybridNames, ScenarioAndConditionNamesRoundTrip) {
  for (WalkScenario s : walk_scenarios(true))
    EXPECT_EQ(parse_walk_scenario(walk_scenario_name(s)), s) << walk_scenario_name(s);
  EXPECT_EQ(std::string(walk_scenario_name(WalkScenario::kMixedOptimal)), "mixed-optimal");
  EXPECT_FALSE(parse_walk_scenario("mixed_optimal"));
  EXPECT_FALSE(parse_walk_scenario(""));
  EXPECT_EQ(walk_scenarios(false).size(), 5u);
  EXPECT_EQ(walk_scenarios(true).back(), WalkScenario::kFullCulled);
  for (DiagnosisCondition c :
       {DiagnosisCondition::kScene, DiagnosisCondition::kSky, DiagnosisCondition::kScene4})
    EXPECT_EQ(parse_diagnosis_condition(diagnosis_condition_name(c)), c);
  EXPECT_FALSE(parse_diagnosis_condition("scene2"));
}

TEST(HybridWalkthrough, BudgetSweepRowsPerCheckpointScenarioAndFraction) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  tstest::TempDir dir;
  std::ofstream(dir / "scene.json") << tstest::small_hybrid_scene(data);
  HybridBenchOptions o = reduced_options(dir);
  o.mode = HybridMode::kBudgetSweep;
  o.budget_fractions = {0.25, 1.0};
  o.cost_split = 1;
  const Terrain terrain = load_terrain(TerrainOptions{});
  const HybridBenchResult r = run_hybrid(o, {terrain, {}, {}});

  EXPECT_EQ(r.mode, HybridMode::kBudgetSweep);
  EXPECT_TRUE(r.scenarios.empty());
  ASSERT_FALSE(r.budget_sweep.empty());
  std::set<std::string> checkpoints, scenarios;
  for (const BudgetSweepRow& row : r.budget_sweep) {
    checkpoints.insert(row.checkpoint);
    scenarios.insert(row.scenario);
    EXPECT_TRUE(row.fraction == 0.25 || row.fraction == 1.0) << row.fraction;
    EXPECT_NEAR(row.budget_ms, row.fraction * row.full_predicted_ms, 1e-9);
    EXPECT_GE(row.ssim_objects, 0.0);
    EXPECT_LE(row.ssim_objects, 1.0);
    EXPECT_LE(row.ssim, 1.0);
    ASSERT_TRUE(row.cost_split.has_value());
    int drawn = 0;
    for (const CostSplitRow& k : *row.cost_split) {
      EXPECT_EQ(k.instances, row.by_kind[std::size_t(k.kind)]);
      drawn += k.instances;
    }
    EXPECT_EQ(drawn, row.by_kind[0] + row.by_kind[1] + row.by_kind[2]);
  }
  EXPECT_EQ(r.budget_sweep.size(), checkpoints.size() * scenarios.size() * 2);

  const nlohmann::json j = report::budget_sweep_json(r.budget_sweep);
  ASSERT_EQ(j.size(), r.budget_sweep.size());
  EXPECT_EQ(j[0]["scenario"], r.budget_sweep[0].scenario);
  EXPECT_EQ(j[0]["by_kind"].size(), 3u);
  EXPECT_TRUE(j[0]["cost_split"].is_array());
}

TEST(HybridWalkthrough, QualityDiagnosisRowsPerGroupAndRepresentation) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  tstest::TempDir dir;
  std::ofstream(dir / "scene.json") << tstest::small_hybrid_scene(data);
  HybridBenchOptions o = reduced_options(dir);
  o.mode = HybridMode::kQualityDiagnosis;
  o.diagnosis_conditions = {DiagnosisCondition::kScene};
  o.width = 64;  // every group, representation and checkpoint is drawn: keep them small
  o.height = 36;
  o.msaa = 1;
  const Terrain terrain = load_terrain(TerrainOptions{});
  const HybridBenchResult r = run_hybrid(o, {terrain, {}, {}});

  EXPECT_EQ(r.mode, HybridMode::kQualityDiagnosis);
  ASSERT_FALSE(r.quality_diagnosis.empty());
  std::set<std::string> representations;
  for (const DiagnosisRow& row : r.quality_diagnosis) {
    EXPECT_EQ(row.condition, DiagnosisCondition::kScene);
    EXPECT_GT(row.instances, 0u);
    EXPECT_GE(row.measured, 0.0);
    EXPECT_LE(row.measured, 1.0);
    EXPECT_GT(row.predicted, 0.0);
    EXPECT_LE(row.predicted, 1.0);
    EXPECT_FALSE(row.predicted_context);  // no tables in context asked for
    representations.insert(row.representation);
  }
  EXPECT_GT(representations.size(), 1u);

  const nlohmann::json j = report::quality_diagnosis_json(r.quality_diagnosis);
  ASSERT_EQ(j.size(), r.quality_diagnosis.size());
  EXPECT_EQ(j[0]["condition"], "scene");
  EXPECT_FALSE(j[0].contains("predicted_context"));
}

TEST(HybridWalkthrough, ReducedRunInProcess) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  tstest::TempDir dir;
  std::ofstream(dir / "scene.json") << tstest::small_hybrid_scene(data);
  const HybridBenchOptions o = reduced_options(dir);
  const Terrain terrain = load_terrain(TerrainOptions{});
  const HybridBenchResult r = run_hybrid(o, {terrain, {}, {}});

  EXPECT_EQ(r.mode, HybridMode::kWalkthrough);
  EXPECT_EQ(r.target_ms, 40.0);
  EXPECT_FALSE(r.target_auto);
  EXPECT_GT(r.full_ms_at_start, 0.0);
  EXPECT_EQ(r.width, 160);
  EXPECT_EQ(r.height, 90);
  EXPECT_EQ(r.frames, 10);
  EXPECT_EQ(r.msaa, 4);
  EXPECT_EQ(r.instances, 12);
  EXPECT_GT(r.full_triangles_max, 0);
  EXPECT_FALSE(r.quality_context);
  EXPECT_TRUE(r.quality_diagnosis.empty());
  EXPECT_TRUE(r.budget_sweep.empty());
  EXPECT_FALSE(r.calibration.empty());

  ASSERT_EQ(r.scenarios.size(), 6u);
  const std::vector<WalkScenario> order = walk_scenarios(true);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const HybridScenarioResult& s = r.scenarios[k];
    const std::string name = walk_scenario_name(s.scenario);
    EXPECT_EQ(s.scenario, order[k]);
    // Full geometry is the reference, drawn on scored frames only.
    const std::size_t drawn = s.scenario == WalkScenario::kFull ? 5 : 10;
    ASSERT_EQ(s.frames.size(), drawn) << name;
    EXPECT_EQ(s.ms.count, int(drawn)) << name;
    for (const HybridFrame& f : s.frames) {
      EXPECT_TRUE(f.selection) << name << " frame " << f.drawn.frame;
      // Scored frames carry the object-masked SSIM, the others nothing.
      EXPECT_EQ(f.ssim_objects.has_value(), f.drawn.frame % 2 == 0 && k > 0)
          << name << " frame " << f.drawn.frame;
      if (f.ssim_objects) {
        EXPECT_LE(*f.ssim_objects, 1.0);
        EXPECT_GT(*f.ssim_objects, 0.0);
      }
    }
    ASSERT_EQ(s.checkpoints.size(), 5u) << name;
    for (const HybridCheckpoint& c : s.checkpoints) {
      EXPECT_EQ(c.frame % 2, 0) << name << " " << c.name;
      if (s.scenario == WalkScenario::kFull || s.scenario == WalkScenario::kFullCulled) {
        EXPECT_EQ(c.ssim, 1.0) << name << " " << c.name;
        EXPECT_EQ(c.psnr, kPsnrCapDb) << name << " " << c.name;
      }
    }
  }
  // Culling what the terrain hides: something is hidden on this path, and
  // only the culling scenarios leave anything out.
  EXPECT_GT(r.scenario(WalkScenario::kFullCulled)->occluded_per_frame, 0.5);
  EXPECT_EQ(r.scenario(WalkScenario::kFull)->occluded_per_frame, 0.0);

  EXPECT_EQ(r.selection.policy, SelectionPolicy::kOptimal);
  EXPECT_GT(r.selection.frames, 0);
  EXPECT_GT(r.selection.policy_ms_per_frame, 0.0);
  EXPECT_LE(r.selection.policy_ms_per_frame, r.selection.ms_per_frame);
  EXPECT_GE(r.selection.objective_optimal, r.selection.objective_greedy);
  EXPECT_GE(r.selection.gain_max, r.selection.gain_mean);

  // Figure 6 at checkpoint C: every scenario's image, in the scenarios' order.
  EXPECT_EQ(r.figure6_checkpoint, "C");
  ASSERT_EQ(r.figure6.size(), 6u);
  for (std::size_t k = 0; k < order.size(); ++k) {
    EXPECT_EQ(r.figure6[k].first, order[k]);
    EXPECT_EQ(r.figure6[k].second.width, 160);
    EXPECT_EQ(r.figure6[k].second.height, 90);
  }

  // The report from the typed result, and the controller replayed on it.
  {
    OutputDir out(dir / "h");
    report::write_hybrid_report(r, out);
    report::write_json(report::hybrid_json(r), out.file("hybrid.json"), {});
    out.commit();
  }
  for (const char* f : {"index.html", "table2.md", "fig6_mixed-optimal.png", "frames_pm.dat"})
    EXPECT_TRUE(std::filesystem::exists(dir / ("h/" + std::string(f)))) << f;
  const std::vector<RecordedFrame> pm = read_recorded_frames(dir / "h/frames_pm.dat");
  ASSERT_EQ(pm.size(), 10u);
  EXPECT_EQ(pm[3].ms, r.scenario(WalkScenario::kPm)->frames[3].drawn.ms);
  EXPECT_EQ(recorded_target_ms(dir / "h"), 40.0);
  ControllerReplayOptions ro;
  ro.runs = {dir / "h"};
  const ControllerReplayResult rp = run_controller_replay(ro);
  ASSERT_EQ(rp.series.size(), 2u);
  EXPECT_EQ(rp.series[0].scenario, WalkScenario::kPm);
  EXPECT_EQ(rp.series[1].scenario, WalkScenario::kMixedOptimal);
  for (const ReplaySeries& s : rp.series) {
    EXPECT_EQ(s.frames, 10u);
    EXPECT_EQ(s.target_ms, 40.0);
    EXPECT_EQ(s.recorded_budget_ms.size(), 10u);
    EXPECT_EQ(s.replayed_budget_ms.size(), 10u);
    EXPECT_GT(s.replayed_budget_over_target, 0.0);
  }
}

}  // namespace
