// SPDX-License-Identifier: MIT
// The voxel study in-process on a tiny terrain: which frames each variant and
// the reference draw, the scores against the reference, the sweeps' shapes
// and the report's JSON.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "experiment_test_util.h"
#include "terrasprite/experiment/voxel.h"
#include "terrasprite/report/voxel_report.h"

namespace terrasprite {
namespace {

Terrain tiny_terrain() { return tiny_synthetic_terrain(65); }

VoxelBenchOptions tiny_options() {
  VoxelBenchOptions o;
  o.width = 64;
  o.height = 48;
  o.frames = 4;
  o.threads = {1};
  o.pitches = {-30, -90};
  o.score_every = 2;
  o.terrain_sizes = {33};
  o.sweep_frames = 2;
  o.supersample = 1;
  return o;
}

TEST(VoxelBench, NaiveAndTheReferenceDrawTheScoredFramesOnly) {
  const Terrain t = tiny_terrain();
  VoxelBenchOptions o = tiny_options();
  std::vector<std::pair<VoxelBenchImage, int>> images;
  o.on_image = [&](VoxelBenchImage kind, int frame, const Image& im) {
    EXPECT_EQ(im.width, 64);
    EXPECT_EQ(im.height, 48);
    images.emplace_back(kind, frame);
  };
  const VoxelBenchResult r = run_voxel_bench(t, o);
  EXPECT_EQ(r.frames, 4);
  EXPECT_EQ(r.scored_frames, 2);  // frames 0 and 2
  ASSERT_EQ(r.variants.size(), 3u);
  EXPECT_EQ(r.variants[0].variant, VoxelVariant::kNaive);
  EXPECT_EQ(r.variants[0].frame_ms.size(), 2u);
  EXPECT_EQ(r.variants[1].frame_ms.size(), 4u);
  EXPECT_EQ(r.variants[2].frame_ms.size(), 4u);
  const std::vector<std::pair<VoxelBenchImage, int>> expected = {
      {VoxelBenchImage::kReference, 0},
      {VoxelBenchImage::kMultires, 0},
      {VoxelBenchImage::kReference, 2},
      {VoxelBenchImage::kMultires, 2}};
  EXPECT_EQ(images, expected);
  ASSERT_EQ(r.per_frame.size(), 4u);
  for (const VoxelFrameRow& f : r.per_frame) {
    const bool scored = f.frame % 2 == 0;
    EXPECT_EQ(f.reference_ms.has_value(), scored) << f.frame;
    EXPECT_EQ(f.ms[0].has_value(), scored) << f.frame;  // naive
    EXPECT_TRUE(f.ms[2].has_value()) << f.frame;
    EXPECT_EQ(f.ssim[2].has_value(), scored) << f.frame;
  }
}

TEST(VoxelBench, ScoresAgainstTheReferenceAndSweepsEachSetting) {
  const Terrain t = tiny_terrain();
  const VoxelBenchResult r = run_voxel_bench(t, tiny_options());
  for (const VoxelVariantResult& v : r.variants) {
    EXPECT_EQ(v.threads, 1);
    EXPECT_EQ(v.ssim.count, 2) << to_string(v.variant);
    EXPECT_GT(v.ssim.mean, 0.3) << to_string(v.variant);
    EXPECT_LE(v.ssim.max, 1.0);
    EXPECT_GT(v.psnr.mean, 12.0) << to_string(v.variant);
    EXPECT_TRUE(std::isnan(v.scaling_2v1));  // one thread count: no 2-vs-1 figure
    ASSERT_EQ(v.median_ms_by_threads.size(), 1u);
    EXPECT_EQ(v.median_ms_by_threads[0].first, 1);
    EXPECT_DOUBLE_EQ(v.ns_per_pixel, v.median_ms * 1e6 / (64.0 * 48));
  }
  EXPECT_DOUBLE_EQ(r.variants[0].speedup_vs_naive, 1.0);
  ASSERT_EQ(r.pitch_table.size(), 2u);
  EXPECT_EQ(r.pitch_table[0].pitch_deg, -30);
  EXPECT_EQ(r.pitch_table[1].pitch_deg, -90);
  for (const VoxelPitchRow& p : r.pitch_table)
    EXPECT_DOUBLE_EQ(p.fps, 1000.0 / std::max(p.median_ms, 1e-9));
  ASSERT_EQ(r.terrain_size_sweep.size(), 1u);
  EXPECT_EQ(r.terrain_size_sweep[0].samples, 33);
  EXPECT_EQ(r.terrain_size_sweep[0].frames, 2);

  const nlohmann::json j = report::voxel_bench_json(r);
  EXPECT_TRUE(j["scaling_2v1"].is_null());
  EXPECT_EQ(j["default_variant"], "multires");
  EXPECT_EQ(j["variants"][2]["frames_timed"], 4);
  EXPECT_EQ(j["variants"][0]["median_ms_by_threads"].size(), 1u);
  EXPECT_EQ(j["per_frame"][1].count("naive_ms"), 0u);
  EXPECT_EQ(j["per_frame"][2].count("naive_ssim"), 1u);
  EXPECT_EQ(j["terrain"]["samples"], nlohmann::json({65, 65}));
}

}  // namespace
}  // namespace terrasprite
