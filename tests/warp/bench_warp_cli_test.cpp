// SPDX-License-Identifier: MIT
// `terrasprite bench warp` end to end on a tiny terrain: the JSON contract,
// the worst-warp diagnosis (which frames, and what the camera did), and bad
// options exiting with status 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace {

namespace fs = std::filesystem;

int run(const std::string& args) {
  return tstest::run_cli(args).status;
}

TEST(BenchWarp, WritesTheContractAndNamesTheWorstWarps) {
  tstest::TempDir tmp;
  const std::string json = (tmp.path / "w.json").string(), out = (tmp.path / "w").string();
  ASSERT_EQ(run("bench warp --synthetic-size 65 --size 96x64 --path paper --frames 12 --k-max 3 "
                "--json " +
                json + " --out " + out),
            0);
  const nlohmann::json d = nlohmann::json::parse(std::ifstream(json));
  for (const char* k : {"size", "renderer", "path", "methods", "flythrough"})
    EXPECT_TRUE(d.contains(k)) << k;
  ASSERT_EQ(d["methods"].size(), 2u);  // poly2 and depth on the one path
  for (const auto& m : d["methods"]) {
    for (const char* k : {"name", "warp_ms_median", "real_ms_median", "cost_fraction", "by_k"})
      EXPECT_TRUE(m.contains(k)) << k;
    ASSERT_EQ(m["by_k"].size(), 3u);
    // 12 frames with real frames 0, 4, 8: 9 warps, the 5 worst listed by
    // rising PSNR, each at its own k (frame = real frame + k).
    const auto& worst = m["worst"];
    ASSERT_EQ(worst.size(), 5u);
    double psnr = -1;
    for (const auto& w : worst) {
      const int k = w["k"], frame = w["frame"];
      EXPECT_GE(k, 1);
      EXPECT_LE(k, 3);
      EXPECT_EQ(frame % 4, k);
      EXPECT_GE(double(w["psnr"]), psnr);
      psnr = w["psnr"];
      EXPECT_GT(double(w["moved_m"]), 0.0);  // the paper path moves every frame
      EXPECT_LE(double(w["turn_deg"]), 180.0);  // an angle between two view directions
      EXPECT_GT(double(w["clearance_m"]), 0.0);  // above the ground
    }
  }
  EXPECT_TRUE(fs::exists(fs::path(out) / "quality_vs_k.dat"));
}

TEST(BenchWarp, BadOptionsExitWithStatus2) {
  tstest::TempDir tmp;
  const std::string o = " --out " + (tmp.path / "w").string();
  EXPECT_EQ(run("bench warp --synthetic-size 65 --k-max 0" + o), 2);
  EXPECT_EQ(run("bench warp --synthetic-size 65 --frames 1" + o), 2);
  EXPECT_EQ(run("bench warp --synthetic-size 65 --renderer lod" + o), 2);
  EXPECT_EQ(run("bench warp --synthetic-size 65 --margin 2" + o), 2);
  EXPECT_FALSE(fs::exists(tmp.path / "w"));  // nothing that looks complete
}

}  // namespace
