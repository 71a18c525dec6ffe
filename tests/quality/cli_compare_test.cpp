// SPDX-License-Identifier: MIT
// `terrasprite compare`: JSON contract, difference images, and bad input
// (exit 2 with one line naming the problem).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "quality_test_util.h"
#include "terrasprite/terrain/image_io.h"
#include "test_util.h"

namespace terrasprite::quality {
namespace {

using testing::noisy;
using testing::scene;

int lines(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

TEST(CliCompare, JsonHasTheKeysAskedForAndInfAsAString) {
  tstest::TempDir dir;
  const Image a = scene(200, 180), b = noisy(a, 5);
  save_png(a, dir / "a.png");
  save_png(b, dir / "b.png");
  auto r = tstest::run_cli("compare " + (dir / "a.png") + " " + (dir / "a.png") + " --json " +
                           (dir / "id.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  auto j = nlohmann::json::parse(std::ifstream(dir / "id.json"));
  EXPECT_EQ(j["psnr_rgb"], "inf");
  EXPECT_EQ(j["psnr_luma"], "inf");
  EXPECT_EQ(j["ssim"], 1.0);
  EXPECT_EQ(j["ssim_channels"].size(), 3u);
  EXPECT_EQ(j["ssim_mode"], "wang");
  EXPECT_EQ(j["flip_mean"], 0.0);
  EXPECT_TRUE(j.contains("msssim") && j.contains("flip_median") && j.contains("ppd"));

  r = tstest::run_cli("compare " + (dir / "a.png") + " " + (dir / "b.png") +
                      " --metrics ssim --ssim-mode ffmpeg --diff " + (dir / "d.png") +
                      " --flip-map " + (dir / "f.png") + " --ppd 40 --json " + (dir / "s.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  j = nlohmann::json::parse(std::ifstream(dir / "s.json"));
  EXPECT_EQ(j["ssim_mode"], "ffmpeg");
  EXPECT_LT(j["ssim"].get<double>(), 1.0);
  EXPECT_FALSE(j.contains("psnr_rgb"));
  EXPECT_EQ(j["ppd"], 40.0);  // --flip-map computes FLIP
  EXPECT_EQ(load_image(dir / "d.png").width, 200);
  EXPECT_EQ(load_image(dir / "f.png").height, 180);

  // Without --json: a small table on stdout.
  r = tstest::run_cli("compare " + (dir / "a.png") + " " + (dir / "b.png"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("psnr_rgb"), std::string::npos);
  EXPECT_NE(r.output.find("flip_mean"), std::string::npos);
}

TEST(CliCompare, BadInputExitsTwoWithOneLine) {
  tstest::TempDir dir;
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
    const auto r = tstest::run_cli("compare " + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.output;
    EXPECT_EQ(lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(c.needle), std::string::npos) << r.output;
  }
}

TEST(CliCompare, DefaultMetricsSkipMsssimOnSmallImages) {
  tstest::TempDir dir;
  save_png(scene(64, 48), dir / "a.png");
  const auto r = tstest::run_cli("compare " + (dir / "a.png") + " " + (dir / "a.png") +
                                 " --json " + (dir / "j.json"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("msssim skipped"), std::string::npos) << r.output;
  const auto j = nlohmann::json::parse(std::ifstream(dir / "j.json"));
  EXPECT_TRUE(j["msssim"].is_null());
  EXPECT_EQ(j["ssim"], 1.0);
}

}  // namespace
}  // namespace terrasprite::quality
