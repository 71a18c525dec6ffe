// SPDX-License-Identifier: MIT
// The warp study in-process on a tiny terrain: which frames are real and
// which warped, the scores by k, the worst warps and the flythrough figure.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"
#include "experiment_test_util.h"
#include "terrasprite/experiment/warp.h"
#include "terrasprite/report/warp_report.h"

namespace terrasprite {
namespace {

Terrain tiny_terrain() { return tiny_synthetic_terrain(65); }

WarpBenchOptions tiny_options() {
  WarpBenchOptions o;
  o.width = 96;
  o.height = 64;
  o.paths = {"paper"};
  o.frames = 12;
  o.k_max = 3;
  return o;
}

TEST(WarpBench, WarpsEachFrameBetweenRealOnesAndScoresItByK) {
  const Terrain t = tiny_terrain();
  const WarpBenchResult r = run_warp_bench(t, tiny_options());
  EXPECT_EQ(r.margin_x, 5);  // 0.05 x 96, rounded
  EXPECT_EQ(r.margin_y, 3);
  ASSERT_EQ(r.runs.size(), 1u);
  EXPECT_EQ(r.runs[0].real_ms.size(), 12u);  // every frame rendered once
  ASSERT_EQ(r.runs[0].methods.size(), 2u);
  for (const WarpMethodRun& m : r.runs[0].methods) {
    EXPECT_EQ(m.warp_ms.size(), 9u);  // real frames 0, 4, 8; the others warped
    ASSERT_EQ(m.by_k.size(), 3u);
    for (int k = 1; k <= 3; ++k)
      for (const WarpScore& s : m.by_k[std::size_t(k - 1)]) {
        EXPECT_EQ(s.k, k);
        EXPECT_EQ(s.frame % 4, k);
        EXPECT_GT(s.moved_m, 0.0);  // the paper path moves every frame
        EXPECT_GT(s.clearance_m, 0.0);
        EXPECT_GE(s.holes, 0.0);
        EXPECT_LE(s.holes, 1.0);
      }
  }
  ASSERT_EQ(r.methods.size(), 2u);
  for (const WarpMethodSummary& m : r.methods) {
    ASSERT_EQ(m.by_k.size(), 3u);
    for (const WarpKSummary& k : m.by_k) EXPECT_EQ(k.samples, 3);
    // The first warp past a real frame is the best one on average.
    EXPECT_GE(m.by_k[0].psnr, m.by_k[2].psnr - 1.0) << to_string(m.method);
    EXPECT_GT(m.by_k[0].psnr, 10.0) << to_string(m.method);  // a warp, not noise
    ASSERT_EQ(m.worst.size(), 5u);
    for (std::size_t i = 1; i < m.worst.size(); ++i)
      EXPECT_LE(m.worst[i - 1].psnr, m.worst[i].psnr);
    EXPECT_DOUBLE_EQ(m.cost_fraction, m.warp_ms_median / m.real_ms_median);
  }
  ASSERT_EQ(r.flythrough.size(), 2u);
  for (const WarpFlythrough& f : r.flythrough) {
    EXPECT_EQ(f.real_every, 4);
    EXPECT_NEAR(f.mean_ms_per_output_frame, (f.real_ms_mean + 3 * f.warp_ms_mean) / 4, 1e-12);
    EXPECT_EQ(f.meets_60hz, f.mean_ms_per_output_frame <= 1000.0 / 60.0);
  }
  const nlohmann::json j = report::warp_bench_json(r);
  EXPECT_EQ(j["renderer"], "voxel");
  EXPECT_EQ(j["margin_px"], nlohmann::json({5, 3}));
  EXPECT_EQ(j["methods"][0]["name"], "poly2");
  EXPECT_EQ(j["methods"][1]["name"], "depth");
}

TEST(WarpBench, ABadPathIsRefusedBeforeAnyFrame) {
  const Terrain t = tiny_terrain();
  WarpBenchOptions o = tiny_options();
  int progress = 0;
  o.paths = {"paper", "/nonexistent/path.json"};
  o.progress = [&](int, int) { ++progress; };
  EXPECT_THROW(run_warp_bench(t, o), InputError);
  EXPECT_EQ(progress, 0);
}

}  // namespace
}  // namespace terrasprite
