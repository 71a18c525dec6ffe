// SPDX-License-Identifier: MIT
// `bench hybrid` at a reduced size: two small models, 12 instances, 10 frames
// at 160 x 90, coarse table sampling (its own cache in a temp dir). Checks
// the JSON contract and the report's files, and runs it again without the
// occlusion culling; no timing is asserted.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>
#include <vector>

#include "hybrid_test_util.h"
#include "test_util.h"

namespace {

TEST(BenchHybrid, ReducedWalkthroughJsonContract) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  tstest::TempDir dir;
  std::ofstream(dir / "scene.json") << tstest::small_hybrid_scene(data);
  const std::string args =
      "bench hybrid --scene " + (dir / "scene.json") +
      " --size 160x90 --frames 10 --score-every 2 --target-ms 40 --table-sizes 64"
      " --table-angle-step 120 --table-headings 0,180 --relief-resolutions 16,32"
      " --octahedral-resolutions 16"
      " --terrain-quads 64 --quality-context-frames 2 --cache " +
      (dir / "cache");
  const tstest::CliResult r =
      tstest::run_cli(args + " --json " + (dir / "h.json") + " --out " + (dir / "h"));
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "h.json"));
  for (const char* k : {"target_ms", "size", "scenarios", "full_triangles_max", "selection"})
    EXPECT_TRUE(j.contains(k)) << k;
  // --llvmpipe-threads auto: the environment's LP_NUM_THREADS when set, else 0
  // on a machine of at most two hardware threads (CI's), the driver's on more.
  EXPECT_EQ(j["msaa"], 4);  // the default: 4 samples a pixel
  ASSERT_TRUE(j.contains("llvmpipe_threads"));
  if (const char* env = std::getenv("LP_NUM_THREADS"))
    EXPECT_EQ(j["llvmpipe_threads"], env);
  else if (std::thread::hardware_concurrency() <= 2)
    EXPECT_EQ(j["llvmpipe_threads"], "0");
  else
    EXPECT_TRUE(j["llvmpipe_threads"].is_null());
  std::set<std::string> names;
  for (const auto& s : j["scenarios"]) {
    names.insert(s["name"].get<std::string>());
    for (const char* k : {"name", "median_ms", "p95_ms", "p99_ms", "within_10pct", "mean_ssim",
                          "switches_per_frame", "occluded_per_frame", "checkpoints"})
      EXPECT_TRUE(s.contains(k)) << k;
    ASSERT_EQ(s["checkpoints"].size(), 5u);  // A-E of the default walkthrough
    for (const auto& c : s["checkpoints"]) {
      for (const char* k : {"name", "frame", "ssim", "ssim_objects", "psnr", "flip"})
        EXPECT_TRUE(c.contains(k)) << k;
      EXPECT_EQ(c["frame"].get<int>() % 2, 0);  // on a scored frame
      // Culling what the terrain hides leaves the image as it was.
      if (s["name"] == "full" || s["name"] == "full-culled") {
        EXPECT_EQ(c["ssim"].get<double>(), 1.0);
        EXPECT_EQ(c["psnr"].get<double>(), 100.0);
      }
    }
  }
  EXPECT_EQ(names,
            (std::set<std::string>{"full", "ibr", "pm", "mixed", "mixed-optimal", "full-culled"}));
  // The path passes behind the terrain (3.1 instances a frame hidden, over the 64-quad grid the
  // objects stand on), so the identical images above are a check of the culling, not of nothing.
  for (const auto& s : j["scenarios"]) {
    if (s["name"] == "full-culled") {
      EXPECT_GT(s["occluded_per_frame"].get<double>(), 0.5);
    }
  }
  const auto& sel = j["selection"];
  for (const char* k : {"policy", "ms_per_frame", "objective_greedy", "objective_optimal",
                        "policy_ms_per_frame", "policy_ms_p95", "view_ms_per_frame", "view_ms_p95"})
    EXPECT_TRUE(sel.contains(k)) << k;
  // The policy is part of each frame's selection, so of its median too.
  EXPECT_GT(sel["policy_ms_per_frame"].get<double>(), 0.0);
  EXPECT_LE(sel["policy_ms_per_frame"].get<double>(), sel["ms_per_frame"].get<double>());
  // Every frame views some instance, on whichever thread.
  EXPECT_GT(sel["view_ms_per_frame"].get<double>(), 0.0);
  EXPECT_GE(sel["objective_optimal"].get<double>(), sel["objective_greedy"].get<double>());
  // The tables in context: an error scale per (model, representation) seen
  // in the context views (this short path's may show none).
  ASSERT_TRUE(j.contains("quality_context"));
  EXPECT_TRUE(j["quality_context"].is_array());
  for (const auto& q : j["quality_context"]) {
    EXPECT_GE(q["error_scale"].get<double>(), 0.25);
    EXPECT_LE(q["error_scale"].get<double>(), 8.0);
    EXPECT_GT(q["pixels"].get<double>(), 0.0);
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "h/index.html"));
  EXPECT_TRUE(std::filesystem::exists(dir / "h/table2.md"));
  EXPECT_TRUE(std::filesystem::exists(dir / "h/fig6_mixed-optimal.png"));

  // Without the culling (same tables, from the cache: about a second) nothing
  // is hidden and there is no full-culled scenario.
  // An explicit thread count is what the run records (and llvmpipe reads).
  const tstest::CliResult nc =
      tstest::run_cli(args + " --no-occlusion-cull --llvmpipe-threads 1 --json " +
                      (dir / "n.json") + " --out " + (dir / "n"));
  ASSERT_EQ(nc.status, 0) << nc.output;
  const nlohmann::json nj = nlohmann::json::parse(std::ifstream(dir / "n.json"));
  EXPECT_EQ(nj["llvmpipe_threads"], "1");
  ASSERT_EQ(nj["scenarios"].size(), 5u);
  for (const auto& s : nj["scenarios"]) {
    EXPECT_NE(s["name"], "full-culled");
    EXPECT_EQ(s["occluded_per_frame"].get<double>(), 0.0) << s["name"];
  }

  // One sample a pixel (the tables are measured again, under their own key:
  // about 3 s): recorded, and culling what the terrain hides leaves every
  // checkpoint as it was, as it does multisampled (above, where the culling
  // reads one sample's depth).
  const tstest::CliResult ms =
      tstest::run_cli(args + " --msaa 1 --json " + (dir / "m.json") + " --out " + (dir / "m"));
  ASSERT_EQ(ms.status, 0) << ms.output;
  const nlohmann::json mj = nlohmann::json::parse(std::ifstream(dir / "m.json"));
  EXPECT_EQ(mj["msaa"], 1);
  for (const auto& s : mj["scenarios"]) {
    if (s["name"] != "full-culled") continue;
    for (const auto& c : s["checkpoints"]) {
      EXPECT_EQ(c["ssim"].get<double>(), 1.0) << c["name"];
    }
  }

  // The controller replayed on this run's frames (well under a second).
  const tstest::CliResult rp = tstest::run_cli(
      "bench replay-controller " + (dir / "h") +
      " --margin 0 --drift 0.02 --quantile-min-frames 5 --json " + (dir / "r.json"));
  ASSERT_EQ(rp.status, 0) << rp.output;
  const nlohmann::json rj = nlohmann::json::parse(std::ifstream(dir / "r.json"));
  ASSERT_EQ(rj["series"].size(), 2u);  // pm, mixed-optimal
  for (const auto& s : rj["series"]) {
    EXPECT_EQ(s["frames"].get<int>(), 10);
    EXPECT_GT(s["replayed_p95_over_target"].get<double>(), 0.0);
    EXPECT_GT(s["replayed_budget_over_target"].get<double>(), 0.0);
    EXPECT_EQ(s["recorded_budget_ms"].size(), 10u);
    EXPECT_EQ(s["replayed_budget_ms"].size(), 10u);
    EXPECT_GT(s["replayed_budget_ms"][9].get<double>(), 0.0);
  }
  EXPECT_EQ(rj["controller"]["quantile_margin"].get<double>(), 0.0);
  EXPECT_EQ(rj["controller"]["drift"].get<double>(), 0.02);
  EXPECT_EQ(rj["controller"]["quantile_min_frames"].get<int>(), 5);
}

TEST(BenchReplayController, BadRunsExitTwoNamingTheFile) {
  tstest::TempDir dir;
  std::filesystem::create_directories(dir.path / "run");
  std::ofstream(dir / "run/hybrid.json") << R"({"target_ms": 10})";
  std::ofstream(dir / "run/frames_pm.dat") << "frame ms predicted_ms budget_ms\n0 9 8 8\n1 9 x 8\n";
  std::ofstream(dir / "run/frames_mixed-optimal.dat") << "frame ms\n0 9\n";
  std::ofstream(dir / "run/frames_mixed.dat")
      << "frame ms predicted_ms budget_ms\n0 9 8 8\n1 NaN 8 8\n";
  std::ofstream(dir / "run/frames_full.dat") << "frame ms predicted_ms budget_ms\n0 9 8 -inf\n";
  struct Case {
    std::string args, names;
  };
  for (const Case& c : std::vector<Case>{
           {dir / "nothing", "hybrid.json"},
           {dir / "run" + " --scenarios pm", "line 3: 'x' is not a number"},
           {dir / "run" + " --scenarios mixed-optimal", "no 'predicted_ms' column"},
           {dir / "run" + " --scenarios mixed", "line 3: ms nan: a frame time"},
           {dir / "run" + " --scenarios full", "line 2: budget_ms -inf"},
           {dir / "run" + " --scenarios ibr", "frames_ibr.dat: no such frames file"}}) {
    const tstest::CliResult r =
        tstest::run_cli("bench replay-controller " + c.args + " --json " + (dir / "r.json"));
    EXPECT_EQ(r.status, 2) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.names), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "r.json")) << c.args;
  }
}

TEST(BenchHybrid, BadInputExitsTwoWithoutOutput) {
  tstest::TempDir dir;
  std::ofstream(dir / "path.json")
      << R"({"keyframes": [{"t": 0, "position": [0, 0, 50], "yaw_deg": 0},
    {"t": 2, "position": [10, 0, 50], "yaw_deg": 0}], "checkpoints": [{"name": "A", "t": 5}]})";
  // The sizes are checked before the tables are measured (minutes when not cached).
  // clang-format off
  const std::vector<std::string> bad_args{
      "--target-ms 0", "--path " + (dir / "path.json"), "--size 0x0",
      "--budget-fractions 0.1,x", "--diagnosis-conditions scene,moon", "--cull-px -1",
      "--p95-margin -1", "--p95-aim 0.4", "--cost-split 3", "--cost-split -1", "--llvmpipe-threads x",
      "--llvmpipe-threads -1", "--llvmpipe-threads 33", "--llvmpipe-threads 2x", "--msaa 0",
      "--msaa 65", "--msaa 64",  // 64: over what any GL offers
      "--table-sizes 3", "--table-sizes 2049", "--table-sizes 16,x", "--calibration-sizes 2",
      "--calibration-sizes 9000", "--table-headings 360", "--table-headings -5",
      "--table-headings 0,90,0", "--table-headings 0,x", "--quality-spread-penalty -1"};
  // clang-format on
  for (const std::string& bad : bad_args) {
    const tstest::CliResult r =
        tstest::run_cli("bench hybrid --frames 4 " + bad + " --out " + (dir / "o"));
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "o")) << bad;
  }
}

}  // namespace
