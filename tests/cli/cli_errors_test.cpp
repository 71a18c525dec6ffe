// SPDX-License-Identifier: MIT
// Every bad input: one line naming the input, exit status 2, nothing that
// looks like complete output.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace {

void expect_usage_error(const std::string& args, const std::string& fragment) {
  tstest::CliResult r = tstest::run_cli(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find(fragment), std::string::npos) << args << "\n" << r.output;
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
}

}  // namespace

TEST(CliErrors, MissingUnreadableAndUnsupportedFiles) {
  tstest::TempDir tmp;
  expect_usage_error("info --dem /nonexistent/x.tif", "/nonexistent/x.tif: no such file");
  std::ofstream(tmp / "junk.tif") << "this is not a raster";
  expect_usage_error("info --dem " + (tmp / "junk.tif"), "junk.tif: not a readable height raster");
  std::ofstream(tmp / "trunc.png") << "\x89PNG\r\n\x1a\n\0\0";
  expect_usage_error("info --dem " + (tmp / "trunc.png"), "trunc.png");
  expect_usage_error("info --dem " + tmp.path.string(), "is a directory");
  expect_usage_error("render --frames 1 --out " + (tmp / "o") + " --texture /nonexistent/t.png",
                     "/nonexistent/t.png: no such file");
  EXPECT_FALSE(std::filesystem::exists(tmp / "o"));
  EXPECT_FALSE(std::filesystem::exists(tmp / "o.partial"));
}

TEST(CliErrors, AbsurdSizesAndCounts) {
  tstest::TempDir tmp;
  const std::string out = " --out " + (tmp / "z");
  expect_usage_error("render --size 0x0 --frames 1" + out, "--size 0x0");
  expect_usage_error("render --size -5x10 --frames 1" + out, "--size -5x10");
  expect_usage_error("render --size 100000x100 --frames 1" + out, "--size 100000x100");
  expect_usage_error("render --size banana --frames 1" + out, "--size banana");
  expect_usage_error("render --frames 0" + out, "--frames 0");
  expect_usage_error("info --resample 1", "--resample 1");
  expect_usage_error("info --synthetic-size 1", "--synthetic-size");
  expect_usage_error("info --spacing -3", "--spacing");
  expect_usage_error("render --mode lod --lod-quads 0 --frames 1" + out, "--lod-quads 0");
  EXPECT_FALSE(std::filesystem::exists(tmp / "z"));
}

TEST(CliErrors, MalformedPathFiles) {
  tstest::TempDir tmp;
  const std::string out = " --out " + (tmp / "z");
  expect_usage_error("render --frames 1 --path " + (tmp / "missing.json") + out,
                     "missing.json: no such path file");
  std::ofstream(tmp / "bad.json") << "{\"keyframes\": [{\"t\": 0, \"position\": [1, 2]}]}";
  expect_usage_error("render --frames 1 --path " + (tmp / "bad.json") + out,
                     "position must be an array of 3 numbers");
  EXPECT_FALSE(std::filesystem::exists(tmp / "z"));
}

TEST(CliErrors, UsageErrorsFromTheParser) {
  expect_usage_error("render --no-such-option", "--no-such-option");
  expect_usage_error("render --mode bogus --out x", "bogus");
  expect_usage_error("", "subcommand");
  expect_usage_error("info --encoding rgb", "rgb");
}

// The soak's memory curve: RSS sampled every --memory-every frames (and at
// frame 0), the peak at least the largest sample, growth a finite number.
TEST(Cli, RenderRecordsItsMemoryCurve) {
  tstest::TempDir tmp;
  tstest::CliResult r = tstest::run_cli(
      "render --synthetic-size 65 --mode sprite --lod-quads 8 --frames 7 --size 32x32 "
      "--no-images --memory-every 3 --out " +
      (tmp / "r"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream js(tmp.path / "r" / "stats.json");
  const nlohmann::json m = nlohmann::json::parse(js)["memory"];
  ASSERT_EQ(m["rss_mb"].size(), 3u) << m.dump();  // frames 0, 3, 6
  double most = 0;
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(m["rss_mb"][k][0], 3 * k);
    EXPECT_GT(double(m["rss_mb"][k][1]), 1.0);  // a GL process holds megabytes
    most = std::max(most, double(m["rss_mb"][k][1]));
  }
  EXPECT_GE(double(m["peak_rss_mb"]), most);
  EXPECT_TRUE(m["heap_trim"]);
  EXPECT_TRUE(m["growth_mb_per_10k_frames_after_1000"].is_number());
  r = tstest::run_cli("render --synthetic-size 65 --frames 2 --size 8x8 --memory-every 0 --out " +
                      (tmp / "z"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--memory-every"), std::string::npos) << r.output;
}

TEST(CliErrors, AllNodataRasterIsAnError) {
  tstest::TempDir tmp;
  // An ASCII grid whose every cell is nodata.
  std::ofstream(tmp / "n.asc")
      << "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 30\nNODATA_value -9999\n"
         "-9999 -9999 -9999\n-9999 -9999 -9999\n-9999 -9999 -9999\n";
  expect_usage_error("info --dem " + (tmp / "n.asc"), "all cells are nodata");
}

TEST(Cli, RenderWritesFramesDepthAndStatsThenInfoJson) {
  tstest::TempDir tmp;
  tstest::CliResult r = tstest::run_cli(
      "render --synthetic-size 65 --mode lod --lod-quads 8 --frames 2 --size 48x32 --depth --out " +
      (tmp / "r") + " --json " + (tmp / "s.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"frame_0000.png", "frame_0001.png", "depth_0000.png", "stats.json"})
    EXPECT_TRUE(std::filesystem::exists(tmp.path / "r" / f)) << f;
  EXPECT_FALSE(std::filesystem::exists(tmp / "r.partial"));
  std::ifstream js(tmp / "s.json");
  std::string text((std::istreambuf_iterator<char>(js)), {});
  EXPECT_NE(text.find("\"gl_renderer\""), std::string::npos);
  EXPECT_NE(text.find("\"class\": \"lod\""), std::string::npos);
  r = tstest::run_cli("info --synthetic-size 65 --resample 33 --json " + (tmp / "i.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream ji(tmp / "i.json");
  std::string info((std::istreambuf_iterator<char>(ji)), {});
  EXPECT_NE(info.find("\"resampled_to\": [\n    33,\n    33\n  ]"), std::string::npos) << info;
}
