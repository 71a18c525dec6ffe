// SPDX-License-Identifier: MIT
// Videos through ffmpeg: exact frame count, rate and size by ffprobe; failures
// are one line and leave no file; split-and-join by frame range matches one run.
#include "terrasprite/output/video_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"
#include "test_util.h"

namespace fs = std::filesystem;
using terrasprite::Image;
using terrasprite::InputError;
using terrasprite::VideoOptions;
using terrasprite::VideoWriter;

namespace {

struct Probe {
  int frames = -1, width = -1, height = -1;
  std::string rate, pix_fmt, codec;
};

Probe probe(const std::string& file) {
  auto j = nlohmann::json::parse(
      tstest::run_shell("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                        "stream=nb_read_frames,width,height,r_frame_rate,pix_fmt,codec_name "
                        "-of json '" +
                        file + "' 2>/dev/null")
          .output,
      nullptr, false);
  Probe p;
  if (j.is_discarded() || j["streams"].empty()) return p;
  const auto& s = j["streams"][0];
  p.frames = std::stoi(s.value("nb_read_frames", "-1"));
  p.width = s.value("width", -1);
  p.height = s.value("height", -1);
  p.rate = s.value("r_frame_rate", "");
  p.pix_fmt = s.value("pix_fmt", "");
  p.codec = s.value("codec_name", "");
  return p;
}

/// Decoded RGB bytes of every frame.
std::string decode(const std::string& file) {
  return tstest::run_shell("ffmpeg -v error -i '" + file +
                           "' -f rawvideo -pix_fmt rgb24 - 2>/dev/null")
      .output;
}

double psnr(const std::string& a, const std::string& b) {
  double se = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    double d = double(std::uint8_t(a[i])) - std::uint8_t(b[i]);
    se += d * d;
  }
  double mse = se / double(a.size());
  return mse == 0 ? 99.0 : 10 * std::log10(255.0 * 255.0 / mse);
}

Image gradient(int w, int h, int t) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.px(x, y);
      p[0] = std::uint8_t(x * 4 + t * 8);
      p[1] = std::uint8_t(y * 4);
      p[2] = std::uint8_t(t * 16);
      p[3] = 255;
    }
  return img;
}

#define REQUIRE_FFMPEG() \
  if (!tstest::have_tool("ffmpeg") || !tstest::have_tool("ffprobe")) GTEST_SKIP() << "no ffmpeg"

}  // namespace

TEST(VideoWriter, ExactFramesRateAndSize) {
  REQUIRE_FFMPEG();
  tstest::TempDir tmp;
  VideoOptions o;
  o.fps = 25;
  VideoWriter v(tmp / "a.mp4", 64, 48, o);
  for (int t = 0; t < 7; ++t) v.push(gradient(64, 48, t));
  EXPECT_FALSE(fs::exists(tmp / "a.mp4"));  // nothing complete-looking before finish()
  v.finish();
  Probe p = probe(tmp / "a.mp4");
  EXPECT_EQ(p.frames, 7);
  EXPECT_EQ(p.width, 64);
  EXPECT_EQ(p.height, 48);
  EXPECT_EQ(p.rate, "25/1");
  EXPECT_EQ(p.pix_fmt, "yuv420p");
  EXPECT_EQ(p.codec, "h264");
  EXPECT_FALSE(fs::exists(tmp / "a.mp4.partial"));
}

TEST(VideoWriter, OddSizeIsPaddedByOnePixel) {
  REQUIRE_FFMPEG();
  tstest::TempDir tmp;
  VideoWriter v(tmp / "odd.mp4", 33, 17);
  EXPECT_TRUE(v.padded());
  EXPECT_EQ(v.encoded_width(), 34);
  EXPECT_EQ(v.encoded_height(), 18);
  for (int t = 0; t < 3; ++t) v.push(gradient(33, 17, t));
  v.finish();
  Probe p = probe(tmp / "odd.mp4");
  EXPECT_EQ(p.frames, 3);
  EXPECT_EQ(p.width, 34);
  EXPECT_EQ(p.height, 18);
}

TEST(VideoWriter, FailingEncoderThrowsOneLineAndLeavesNoFile) {
  tstest::TempDir tmp;
  VideoOptions o;
  o.ffmpeg = "/nonexistent/ffmpeg";
  try {
    VideoWriter v(tmp / "x.mp4", 16, 16, o);
    FAIL() << "missing ffmpeg accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("x.mp4: cannot run /nonexistent/ffmpeg"),
              std::string::npos)
        << e.what();
  }
  // An "encoder" that exits at once with an error: the pipe breaks or the exit status says so.
  std::ofstream(tmp / "bad.sh") << "#!/bin/sh\necho 'Unknown encoder libx264' >&2\nexit 1\n";
  fs::permissions(tmp / "bad.sh", fs::perms::owner_all);
  o.ffmpeg = tmp / "bad.sh";
  bool threw = false;
  try {
    VideoWriter v(tmp / "y.mp4", 256, 256, o);
    for (int t = 0; t < 20; ++t) v.push(gradient(256, 256, t));
    v.finish();
  } catch (const InputError& e) {
    threw = true;
    const std::string msg = e.what();
    EXPECT_NE(msg.find("y.mp4: video encoding failed"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  EXPECT_TRUE(threw);
  EXPECT_FALSE(fs::exists(tmp / "y.mp4"));
  for (const auto& e : fs::directory_iterator(tmp.path))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(VideoWriter, AnEncoderThatStopsReadingFailsInsteadOfHanging) {
  tstest::TempDir tmp;
  std::ofstream(tmp / "stuck.sh") << "#!/bin/sh\nexec sleep 60\n";
  fs::permissions(tmp / "stuck.sh", fs::perms::owner_all);
  VideoOptions o;
  o.ffmpeg = tmp / "stuck.sh";
  o.stall_seconds = 0.5;
  try {
    VideoWriter v(tmp / "s.mp4", 256, 256, o);
    for (int t = 0; t < 40; ++t) v.push(gradient(256, 256, t));
    v.finish();
    FAIL() << "a stuck encoder was waited for";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.mp4: video encoding failed (ffmpeg read nothing for "
                                         "0.5 s"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(tmp / "s.mp4"));
  for (const auto& e : fs::directory_iterator(tmp.path))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(VideoWriter, BadOptionsAreInputErrors) {
  VideoOptions o;
  o.preset = "warp9";
  EXPECT_THROW(terrasprite::validate_video_options(o), InputError);
  o = {};
  o.crf = 60;
  EXPECT_THROW(terrasprite::validate_video_options(o), InputError);
  o = {};
  o.fps = 0;
  EXPECT_THROW(terrasprite::validate_video_options(o), InputError);
}

TEST(RenderVideo, CliFailuresExitTwoWithOneLine) {
  tstest::TempDir tmp;
  auto r = tstest::run_cli("render --mode full --frames 2 --size 32x32 --video " + (tmp / "v.mp4") +
                           " --preset warp9");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  r = tstest::run_cli("render --mode full --frames 2 --size 32x32 --frame-range 1:5 --video " +
                      (tmp / "v.mp4"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--frame-range 1:5"), std::string::npos) << r.output;
  // ffmpeg missing: one line, exit 2, no video, no output directory.
  r = tstest::run_cli_prefixed("env TERRASPRITE_FFMPEG=/nonexistent/ffmpeg",
                               "render --mode full --frames 2 --size 32x32 --video " +
                                   (tmp / "n.mp4") + " --out " + (tmp / "o4"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("cannot run /nonexistent/ffmpeg"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(tmp / "n.mp4"));
  EXPECT_FALSE(fs::exists(tmp / "o4"));
}

TEST(RenderVideo, SplitByFrameRangeJoinsToTheSingleRun) {
  REQUIRE_FFMPEG();
  tstest::TempDir tmp;
  // Near-lossless (crf 8): the two encodings then differ by GOP structure, not by x264 noise.
  const std::string common =
      "render --mode full --frames 12 --size 96x64 --fps 24 --crf 8 --no-images";
  auto r = tstest::run_cli(common + " --video " + (tmp / "all.mp4"));
  ASSERT_EQ(r.status, 0) << r.output;
  r = tstest::run_cli(common + " --frame-range 0:5 --video " + (tmp / "a.mp4"));
  ASSERT_EQ(r.status, 0) << r.output;
  r = tstest::run_cli(common + " --frame-range 5:12 --video " + (tmp / "b.mp4") + " --json " +
                      (tmp / "b.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  auto j = nlohmann::json::parse(std::ifstream(tmp / "b.json"));
  EXPECT_EQ(j["frame_range"], nlohmann::json({5, 12}));
  EXPECT_EQ(j["frames"].size(), 7u);
  EXPECT_EQ(j["frames"][0]["frame"], 5);
  std::ofstream(tmp / "list.txt") << "file '" << (tmp / "a.mp4") << "'\nfile '" << (tmp / "b.mp4")
                                  << "'\n";
  const auto joined_run =
      tstest::run_shell("ffmpeg -v error -f concat -safe 0 -i '" + (tmp / "list.txt") +
                        "' -c copy '" + (tmp / "joined.mp4") + "'");
  ASSERT_EQ(joined_run.status, 0) << joined_run.output;
  Probe all = probe(tmp / "all.mp4"), joined = probe(tmp / "joined.mp4");
  EXPECT_EQ(all.frames, 12);
  EXPECT_EQ(joined.frames, 12);
  EXPECT_EQ(all.rate, "24/1");  // (the concat demuxer's guess for the joined file is 24000/1001)
  const std::string da = decode(tmp / "all.mp4"), dj = decode(tmp / "joined.mp4");
  ASSERT_EQ(da.size(), std::size_t(96 * 64 * 3 * 12));
  ASSERT_EQ(dj.size(), da.size());
  const std::size_t fb = 96 * 64 * 3;
  for (int f = 0; f < 12; ++f)
    EXPECT_GE(psnr(da.substr(f * fb, fb), dj.substr(f * fb, fb)), 40.0) << "frame " << f;
}
