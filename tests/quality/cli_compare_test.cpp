// SPDX-License-Identifier: MIT
// `terrasprite compare`: JSON contract, difference images, and bad input
// (exit 2 with one line naming the problem).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "quality_test_util.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::quality {
namespace {

using testing::noisy;
using testing::scene;

std::string cli() {
  return TS_CLI;
}

int lines(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

TEST(CliCompare, JsonHasTheKeysAskedForAndInfAsAString) {
  testing::TempDir dir;
  const Image a = scene(200, 180), b = noisy(a, 5);
  save_png(a, dir / "a.png");
  save_png(b, dir / "b.png");
  std::string out;
  ASSERT_EQ(testing::run(cli() + " compare " + (dir / "a.png") + " " + (dir / "a.png") +
                             " --json " + (dir / "id.json"),
                         out),
            0)
      << out;
  auto j = nlohmann::json::parse(std::ifstream(dir / "id.json"));
  EXPECT_EQ(j["psnr_rgb"], "inf");
  EXPECT_EQ(j["psnr_luma"], "inf");
  EXPECT_EQ(j["ssim"], 1.0);
  EXPECT_EQ(j["ssim_channels"].size(), 3u);
  EXPECT_EQ(j["ssim_mode"], "wang");
  EXPECT_EQ(j["flip_mean"], 0.0);
  EXPECT_TRUE(j.contains("msssim") && j.contains("flip_median") && j.contains("ppd"));

  ASSERT_EQ(
      testing::run(cli() + " compare " + (dir / "a.png") + " " + (dir / "b.png") +
                       " --metrics ssim --ssim-mode ffmpeg --diff " + (dir / "d.png") +
                       " --flip-map " + (dir / "f.png") + " --ppd 40 --json " + (dir / "s.json"),
                   out),
      0)
      << out;
  j = nlohmann::json::parse(std::ifstream(dir / "s.json"));
  EXPECT_EQ(j["ssim_mode"], "ffmpeg");
  EXPECT_LT(j["ssim"].get<double>(), 1.0);
  EXPECT_FALSE(j.contains("psnr_rgb"));
  EXPECT_EQ(j["ppd"], 40.0);  // --flip-map computes FLIP
  EXPECT_EQ(load_image(dir / "d.png").width, 200);
  EXPECT_EQ(load_image(dir / "f.png").height, 180);

  // Without --json: a small table on stdout.
  ASSERT_EQ(testing::run(cli() + " compare " + (dir / "a.png") + " " + (dir / "b.png"), out), 0)
      << out;
  EXPECT_NE(out.find("psnr_rgb"), std::string::npos);
  EXPECT_NE(out.find("flip_mean"), std::string::npos);
}

TEST(CliCompare, BadInputExitsTwoWithOneLine) {
  testing::TempDir dir;
  save_png(scene(64, 48), dir / "a.png");
  save_png(scene(64, 50), dir / "taller.png");
  { std::ofstream(dir / "text.png") << "not an image\n"; }
  { std::ofstream(dir / "empty.png"); }
  struct Case {
    std::string args, needle;
  };
  const Case cases[] = {
      {(dir / "a.png") + " " + (dir / "missing.png"), "missing.png: no such file"},
      {(dir / "text.png") + " " + (dir / "a.png"), "text.png"},
      {(dir / "empty.png") + " " + (dir / "a.png"), "empty.png"},
      {(dir / "a.png") + " " + (dir / "taller.png"), "must have the same size"},
      {(dir / "a.png") + " " + (dir / "a.png") + " --metrics psnr,sharpness",
       "unknown metric 'sharpness'"},
      {(dir / "a.png") + " " + (dir / "a.png") + " --metrics msssim", "at least 176"},
      {(dir / "a.png") + " " + (dir / "a.png") + " --ssim-mode matlab", "ssim-mode"},
      {(dir / "a.png") + " " + (dir / "a.png") + " --ppd 0", "pixels per degree"},
      {(dir / "a.png"), "test"},
  };
  for (const Case& c : cases) {
    std::string out;
    EXPECT_EQ(testing::run(cli() + " compare " + c.args, out), 2) << c.args << "\n" << out;
    EXPECT_EQ(lines(out), 1) << out;
    EXPECT_NE(out.find(c.needle), std::string::npos) << out;
  }
}

TEST(CliCompare, DefaultMetricsSkipMsssimOnSmallImages) {
  testing::TempDir dir;
  save_png(scene(64, 48), dir / "a.png");
  std::string out;
  EXPECT_EQ(testing::run(cli() + " compare " + (dir / "a.png") + " " + (dir / "a.png") +
                             " --json " + (dir / "j.json"),
                         out),
            0);
  EXPECT_NE(out.find("msssim skipped"), std::string::npos) << out;
  const auto j = nlohmann::json::parse(std::ifstream(dir / "j.json"));
  EXPECT_TRUE(j["msssim"].is_null());
  EXPECT_EQ(j["ssim"], 1.0);
}

}  // namespace
}  // namespace terrasprite::quality
