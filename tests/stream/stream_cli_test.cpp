// SPDX-License-Identifier: MIT
// `terrasprite tile` and `bench stream` end to end on a tiny terrain: the
// files and JSON keys others rely on, refusal to replace a user's files, an
// injected 30% read-fault rate survived and counted.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace {

TEST(StreamCli, TileThenBenchStreamWritesTheContractKeys) {
  tstest::TempDir t;
  auto r = tstest::run_cli("tile --synthetic-size 129 --tile-size 16 --out " + (t / "tiles"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"height.tif", "color.tif", "bound.tif", "tiles.json"})
    EXPECT_TRUE(std::filesystem::exists(t.path / "tiles" / f)) << f;
  // 16 MB pins the whole 129^2 set, so frames compare with the in-memory peer
  // whatever the loaders' pace (at 1 MB, a loaded machine left none compared:
  // 1 run in 14); loads are exercised by the fault run below and test_stream's
  // StreamingTiles tests.
  r = tstest::run_cli("bench stream --tiles " + (t / "tiles") +
                      " --cache-mb 16 --size 96x64 --frames 8 --json " + (t / "s.json") +
                      " --out " + (t / "s"));
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(t / "s.json"));
  for (const char* k : {"terrain", "cache_mb", "stream", "in_memory", "ratio_median",
                        "faults_injected", "faults_survived"})
    EXPECT_TRUE(j.contains(k)) << k;
  for (const char* k :
       {"median_ms", "p99_ms", "stall_frames", "degraded_samples_total",
        "degraded_fraction_after_warmup", "hit_rate", "io_mb_s", "peak_rss_mb", "first_frame_ms"})
    EXPECT_TRUE(j["stream"].contains(k)) << k;
  EXPECT_EQ(j["images_equal_when_resident"]["frames_compared"],
            j["images_equal_when_resident"]["frames_equal"]);
  EXPECT_GT(j["images_equal_when_resident"]["frames_compared"].get<int>(), 0);
  ASSERT_EQ(j["per_frame"].size(), 8u);
  // The in-memory peer answered every streamed frame (lockstep), and the
  // ratio is the medians' quotient.
  for (const auto& f : j["per_frame"]) EXPECT_GT(f["in_memory_ms"].get<double>(), 0) << f.dump();
  EXPECT_NEAR(j["ratio_median"].get<double>(),
              j["stream"]["median_ms"].get<double>() / j["in_memory"]["median_ms"].get<double>(),
              1e-9);
}

TEST(StreamCli, RefusesADirectoryOfTheUsersAndSurvivesInjectedFaults) {
  tstest::TempDir t;
  std::filesystem::create_directories(t.path / "mine");
  std::ofstream(t / "mine/notes.txt") << "keep me";
  auto r = tstest::run_cli("tile --synthetic-size 65 --out " + (t / "mine"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(std::filesystem::exists(t.path / "mine/notes.txt"));
  ASSERT_EQ(
      tstest::run_cli("tile --synthetic-size 129 --tile-size 16 --out " + (t / "tiles")).status, 0);
  r = tstest::run_cli_prefixed("TERRASPRITE_STREAM_FAULTS=0.3",
                               "bench stream --tiles " + (t / "tiles") +
                                   " --cache-mb 1 --size 96x64 --frames 6 --in-memory no --json " +
                                   (t / "f.json") + " --out " + (t / "f"));
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(t / "f.json"));
  EXPECT_GT(j["faults_injected"].get<int>(), 0);
  EXPECT_EQ(j["faults_survived"], j["faults_injected"]);
  EXPECT_TRUE(j["in_memory"].is_null());
  EXPECT_EQ(
      tstest::run_cli("bench stream --tiles " + (t / "nothing") + " --out " + (t / "n")).status, 2);
  r = tstest::run_cli("bench stream --tiles " + (t / "tiles") + " --first-view-ms -1 --out " +
                      (t / "fv"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--first-view-ms -1"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(t.path / "fv"));
  // The first view's figures are in the JSON.
  EXPECT_EQ(j["stream"]["first_view"]["max_wait_ms"], 600);
  EXPECT_TRUE(j["stream"]["first_frame_parts_ms"].contains("first_view"));
}

TEST(StreamCli, TileStripsRefusesBadSizesInOneLine) {
  tstest::TempDir t;
  auto one_line_error = [&](const std::string& args, const std::string& fragment) {
    const auto r = tstest::run_cli(args + " --out " + (t / "o"));
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(fragment), std::string::npos) << args << "\n" << r.output;
    EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(t / "o"));
    EXPECT_FALSE(std::filesystem::exists(t / "o.partial"));
  };
  one_line_error("tile --synthetic-size 33 --resample 65538", "--resample 65538");
  one_line_error("tile --synthetic-size 33 --resample 20000 --strips never", "--resample 20000");
  one_line_error("tile --synthetic-size 33 --strips sometimes", "--strips");
}

}  // namespace
