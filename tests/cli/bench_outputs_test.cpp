// SPDX-License-Identifier: MIT
// What the benches and render say of what they did: the grid benchmarked, a
// summary instead of the JSON on stdout with --json, the hint for bench
// stream --dem, render's defaults in --help and its warped-frame warning.
// About 10 s in all (small GL and voxel runs).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace {

nlohmann::json read_json(const std::string& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

const std::string kLodsprite =
    "bench lodsprite --synthetic-size 65 --lod-quads 4 --frames 4 --size 32x32 --thresholds 1 "
    "--frame-counts 4 --lod-sweep 4 ";

TEST(BenchOutputs, LodspriteBenchmarksTheInputsOwnGridAndSummarisesWithJson) {
  tstest::TempDir tmp;
  const auto r = tstest::run_cli(kLodsprite + "--json " + tmp / "a.json" + " --out " + tmp / "a");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("\"per_frame\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("65 x 65 samples, the input's own grid"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("targets: keyframes <= 28 n/a"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(tmp / "a.json");
  EXPECT_EQ(j["terrain"]["samples"], nlohmann::json({65, 65}));
  EXPECT_TRUE(j["terrain"]["resampled_from"].is_null());
  EXPECT_TRUE(j["targets"]["keyframes_at_most_28"].is_null());
}

TEST(BenchOutputs, LodspriteResamplesOnlyWhenAskedAndSaysSo) {
  tstest::TempDir tmp;
  const auto r = tstest::run_cli(kLodsprite + "--resample 33 --out " + tmp / "b" + " 2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);  // no --json: the JSON on stdout
  EXPECT_EQ(j["terrain"]["samples"], nlohmann::json({33, 33}));
  EXPECT_EQ(j["terrain"]["resampled_from"], nlohmann::json({65, 65}));
  std::ifstream page(tmp / "b/index.html");
  const std::string html((std::istreambuf_iterator<char>(page)), {});
  EXPECT_NE(html.find("resampled from 65 x 65 by --resample"), std::string::npos);
  EXPECT_NE(html.find("Keyframes by trigger"), std::string::npos);
  EXPECT_NE(html.find("<figcaption>"), std::string::npos);
}

TEST(BenchOutputs, StreamOnADemNamesTheTileCommand) {
  const auto r = tstest::run_cli("bench stream --dem some.tif");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("terrasprite tile --dem some.tif --out DIR"), std::string::npos)
      << r.output;
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST(BenchOutputs, RenderHelpStatesItsDefaults) {
  const auto r = tstest::run_cli("render --help");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* s : {"(default full)", "required unless --video", "'low-fast'",
                        "(default overview)", "--duration"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s;
}

TEST(BenchOutputs, RenderWarnsWhenWarpedFramesAreTooFarAndTakesADuration) {
  tstest::TempDir tmp;
  const std::string base = "render --mode voxel --warp depth --size 32x24 --no-images ";
  const auto far = tstest::run_cli(base + "--frames 12 --out " + tmp / "far");
  ASSERT_EQ(far.status, 0) << far.output;
  EXPECT_NE(far.output.find("warning: --warp depth:"), std::string::npos) << far.output;
  const auto near = tstest::run_cli(base + "--duration 20 --fps 24 --out " + tmp / "near");
  ASSERT_EQ(near.status, 0) << near.output;
  EXPECT_EQ(near.output.find("warning"), std::string::npos) << near.output;
  EXPECT_EQ(read_json(tmp / "near/stats.json")["frames"].size(), 480u);
  const auto both = tstest::run_cli(base + "--frames 3 --duration 2 --out " + tmp / "both");
  EXPECT_EQ(both.status, 2) << both.output;
}

}  // namespace
