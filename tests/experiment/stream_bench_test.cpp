// SPDX-License-Identifier: MIT
// The streaming study in-process on a tiny tile set: the figures computed
// from the frames, alone and with the in-memory peer (the built CLI).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "terrasprite/experiment/stream.h"
#include "terrasprite/report/stream_report.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "test_util.h"

namespace terrasprite {
namespace {

// A 129^2 synthetic terrain in 16-cell tiles.
struct TinyTiles {
  tstest::TempDir dir;
  TinyTiles() {
    TerrainOptions o;
    o.synthetic_size = 129;
    o.erosion_passes = 0;
    TileWriteOptions wo;
    wo.tile_log2 = 4;
    write_tiled_terrain(VoxelTerrain(load_terrain(o)), std::nullopt, dir.path.string(), wo);
  }
};

StreamBenchOptions tiny_options(const TinyTiles& t) {
  StreamBenchOptions o;
  o.tiles = t.dir.path.string();
  o.cache_mb = 16;  // the whole set fits: every frame ends up resident
  o.width = 96;
  o.height = 64;
  o.frames = 8;
  return o;
}

TEST(StreamBench, FiguresAddUpOverTheFramesWithoutAPeer) {
  TinyTiles t;
  int progress = 0;
  StreamBenchOptions o = tiny_options(t);
  o.progress = [&](int, int) { ++progress; };
  const StreamBenchResult r = run_stream_bench(o);
  ASSERT_EQ(r.frames.size(), 8u);
  EXPECT_EQ(progress, 8);
  EXPECT_FALSE(r.in_memory);
  EXPECT_TRUE(std::isnan(r.ratio_median));
  EXPECT_EQ(r.frames_compared, 0);
  long long degraded = 0, bytes = 0;
  for (const StreamFrame& f : r.frames) {
    EXPECT_FALSE(f.in_memory_ms);
    EXPECT_GE(f.ms, f.update_ms);
    degraded += f.stats.degraded_samples;
    bytes += f.stats.bytes_read;
  }
  EXPECT_EQ(r.stream.degraded_samples_total, degraded);
  EXPECT_DOUBLE_EQ(r.stream.bytes_read_mb, double(bytes) / 1e6);
  EXPECT_LE(r.stream.stall_frames, 8);
  EXPECT_GE(r.stream.first_frame_ms, r.stream.open_ms);
  EXPECT_GT(r.stream.pinned_mb, 0.0);
  EXPECT_EQ(r.source.samples_x, 129);
  EXPECT_EQ(r.source.tile_cells, 16);
  EXPECT_FALSE(r.source.cog);

  const nlohmann::json j = report::stream_bench_json(r);
  EXPECT_TRUE(j["in_memory"].is_null());
  EXPECT_TRUE(j["ratio_median"].is_null());
  EXPECT_TRUE(j["cog"].is_null());
  EXPECT_EQ(j["frames"], 8);
  EXPECT_EQ(report::stream_per_frame_json(r).size(), 8u);
}

TEST(StreamBench, ThePeerDrawsTheSameImagesOnceTilesAreResident) {
  TinyTiles t;
  StreamBenchOptions o = tiny_options(t);
  o.in_memory = InMemoryRun::kYes;
  o.peer_command = {TS_CLI,    "bench", "stream", "--tiles",          o.tiles, "--size",
                    "96x64",   "--path", o.path,  "--frames",         "8",     "--threads",
                    "0",       "--first-view-ms", "600", "--in-memory-child"};
  const StreamBenchResult r = run_stream_bench(o);
  ASSERT_TRUE(r.in_memory);
  for (const StreamFrame& f : r.frames) EXPECT_TRUE(f.in_memory_ms);
  EXPECT_GT(r.frames_compared, 0);
  EXPECT_EQ(r.frames_equal, r.frames_compared);
  EXPECT_NEAR(r.ratio_median, r.stream.median_ms / r.in_memory->median_ms, 1e-12);
}

}  // namespace
}  // namespace terrasprite
