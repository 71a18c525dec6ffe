// SPDX-License-Identifier: MIT
// `terrasprite bench lodsprite` end to end on a tiny terrain: the JSON
// contract, the report files, and bad options exiting with status 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace {

namespace fs = std::filesystem;

int run(const std::string& args) {
  return tstest::run_cli(args).status;
}

TEST(BenchLodsprite, WritesTheJsonContractAndTheReport) {
  tstest::TempDir tmp;
  const fs::path dir = tmp.path;
  const std::string json = (dir / "s.json").string(), out = (dir / "report").string();
  ASSERT_EQ(
      run("bench lodsprite --synthetic-size 65 --resample 65 --frames 6 --size 96x96 --lod-quads 4 "
          "--thresholds 0.5,1 --frame-counts 6,12 --lod-sweep 4,8 --json " +
          json + " --out " + out),
      0);
  const nlohmann::json d = nlohmann::json::parse(std::ifstream(json));
  for (const char* k :
       {"gl_renderer", "terrain", "size", "frames", "threshold_px", "full", "lod", "sprite",
        "speedup", "per_frame", "threshold_sweep", "frame_count_sweep", "lod_sweep", "bound"})
    EXPECT_TRUE(d.contains(k)) << k;
  for (const char* k : {"total_ms", "median_ms", "keyframes", "sprite_frames", "key_median_ms",
                        "sprite_median_ms", "mean_psnr", "mean_ssim", "min_ssim", "mean_flip"})
    EXPECT_TRUE(d["sprite"].contains(k)) << k;
  EXPECT_TRUE(d["sprite"].contains("p99_ms"));
  EXPECT_EQ(d["async"], false);
  EXPECT_EQ(d["mesh"], "uniform");
  EXPECT_FALSE(d.contains("cache"));  // only with the cache on
  for (const char* k : {"f", "r", "speedup_bound", "efficiency"})
    EXPECT_TRUE(d["bound"].contains(k)) << k;
  ASSERT_EQ(d["per_frame"].size(), 6u);
  EXPECT_EQ(d["per_frame"][0]["class"], "key");
  EXPECT_EQ(d["per_frame"][0]["error_px"], 0.0);
  // The summary's counts against the per-frame classes they summarise.
  int keys = 0, sprites = 0;
  for (const auto& f : d["per_frame"]) {
    keys += f["class"] == "key";
    sprites += f["class"] == "sprite";
  }
  EXPECT_EQ(keys + sprites, 6);
  EXPECT_EQ(int(d["sprite"]["keyframes"]), keys);
  EXPECT_EQ(int(d["sprite"]["sprite_frames"]), sprites);
  EXPECT_EQ(d["threshold_sweep"].size(), 2u);
  EXPECT_EQ(d["frame_count_sweep"].size(), 2u);
  EXPECT_EQ(d["lod_sweep"].size(), 2u);
  for (const char* file : {"index.html", "lodsprite.json", "fig13_sprite.png",
                           "fig14_diff_sprite.png", "per_frame.dat"})
    EXPECT_TRUE(fs::exists(fs::path(out) / file)) << file;
}

TEST(BenchLodsprite, CacheThereAndBackReportsTheSaving) {
  tstest::TempDir tmp;
  const std::string json = (tmp.path / "c.json").string(), out = (tmp.path / "report").string();
  ASSERT_EQ(
      run("bench lodsprite --synthetic-size 65 --resample 65 --frames 8 --size 96x96 --lod-quads 4 "
          "--there-and-back --cache --thresholds 1 --frame-counts 8 --lod-sweep 4 --json " +
          json + " --out " + out),
      0);
  const nlohmann::json d = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(d["per_frame"].size(), 16u);
  EXPECT_EQ(d["there_and_back"], true);
  ASSERT_TRUE(d.contains("cache"));
  EXPECT_EQ(d["cache"]["size"], 256u << 20);
  EXPECT_EQ(d["cache"]["keyframes"], d["sprite"]["keyframes"]);
  EXPECT_LE(int(d["cache"]["keyframes"]), int(d["cache"]["keyframes_without_cache"]));
}

TEST(BenchLodsprite, BadOptionsExitWithStatus2) {
  EXPECT_EQ(run("bench lodsprite --cache-policy oldest"), 2);
  EXPECT_EQ(run("bench lodsprite --cache-mb -1"), 2);
  EXPECT_EQ(run("bench lodsprite --cache-mb 0.5"), 2);  // under two 512x512 keyframes
  EXPECT_EQ(run("bench lodsprite --cache --cache-accept 0"), 2);
  EXPECT_EQ(run("bench lodsprite --metric fancy"), 2);
  EXPECT_EQ(run("bench lodsprite --mesh fancy"), 2);
  EXPECT_EQ(run("bench lodsprite --mesh adaptive --mesh-triangles 1"), 2);
  EXPECT_EQ(run("bench lodsprite --thresholds 1,abc"), 2);
  EXPECT_EQ(run("bench lodsprite --frame-counts 2.5"), 2);
  EXPECT_EQ(run("bench lodsprite --size 0x0"), 2);
  EXPECT_EQ(run("bench lodsprite --key-margin 0.7"), 2);
  EXPECT_EQ(run("bench lodsprite --key-supersample 0.5"), 2);
  EXPECT_EQ(run("bench lodsprite --scale-per-drape-px -1"), 2);
  EXPECT_EQ(run("bench lodsprite --key-margin 0.1 --metric contrast"), 2);
}

TEST(BenchLodsprite, AdaptiveMeshIsRecorded) {
  tstest::TempDir tmp;
  const std::string json = (tmp.path / "a.json").string(), out = (tmp.path / "report").string();
  ASSERT_EQ(
      run("bench lodsprite --synthetic-size 65 --resample 65 --frames 6 --size 96x96 --lod-quads 4 "
          "--mesh adaptive --thresholds 1 --frame-counts 6 --lod-sweep 4 --json " +
          json + " --out " + out),
      0);
  const nlohmann::json d = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(d["mesh"], "adaptive");
  EXPECT_EQ(d["mesh_triangles"], 32);  // the uniform 4 x 4 grid's, what plain LOD draws
}

// Keyframes framed wider and denser, with the adaptive mesh built for the
// keyframe's wider camera: the run completes and records its framing. CI cost: ~2 s.
TEST(BenchLodsprite, KeyFramingIsRecorded) {
  tstest::TempDir tmp;
  const std::string json = (tmp.path / "k.json").string(), out = (tmp.path / "report").string();
  ASSERT_EQ(
      run("bench lodsprite --synthetic-size 65 --resample 65 --frames 6 --size 96x96 --lod-quads 4 "
          "--mesh adaptive --key-margin 0.125 --key-supersample 1.25 --thresholds 1 "
          "--frame-counts 6 --lod-sweep 4 --json " +
          json + " --out " + out),
      0);
  const nlohmann::json d = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(d["key_margin"], 0.125);
  EXPECT_EQ(d["key_supersample"], 1.25);
  EXPECT_EQ(d["scale_per_drape_px"], 0.0625);
  EXPECT_TRUE(d["per_frame"][0].contains("drape_px"));
  EXPECT_GE(d["sprite"]["keyframes"].get<int>(), 1);
}

TEST(BenchLodsprite, AsyncReportsBothDisplays) {
  tstest::TempDir tmp;
  const std::string json = (tmp.path / "a.json").string(), out = (tmp.path / "report").string();
  ASSERT_EQ(run("bench lodsprite --synthetic-size 65 --resample 65 --frames 12 --size 64x64 "
                "--lod-quads 4 "
                "--async --thresholds 1 --frame-counts 12 --lod-sweep 4 --json " +
                json + " --out " + out),
            0);
  const nlohmann::json d = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(d["async"], true);
  ASSERT_TRUE(d.contains("async_run"));
  const nlohmann::json& a = d["async_run"];
  for (const char* k : {"p99_ms", "p99_over_median", "p99_over_sync_sprite_median", "mean_ssim",
                        "mean_ssim_sync", "mean_psnr", "targets", "method"})
    EXPECT_TRUE(a.contains(k)) << k;
  EXPECT_EQ(double(a["display_hz"]), 60.0);  // paced on a 60 Hz clock by default
  EXPECT_EQ(double(a["async_lead"]), 0.6);   // keyframes requested before the threshold
  for (const char* display : {"sync_display", "async_display"}) {
    EXPECT_EQ(a[display]["frame_ms"].size(), 12u) << display;
    EXPECT_EQ(a[display]["draw_ms"].size(), 12u) << display;
    EXPECT_GT(double(a[display]["median_ms"]), 0.0) << display;
    EXPECT_LE(int(a[display]["late_frames"]), 12) << display;  // at most every frame
  }
  EXPECT_TRUE(std::filesystem::exists(out + "/async.dat"));  // the frame-time plot's data
  EXPECT_EQ(a["async_display"]["keyframes_in_frame"], 1);    // only the first frame waits
  EXPECT_GE(double(a["mean_ssim"]), 0.0);
  EXPECT_LE(double(a["mean_ssim"]), 1.0);
  EXPECT_EQ(run("bench lodsprite --async --cache"), 2);
  EXPECT_EQ(run("bench lodsprite --async --display-hz -1"), 2);
  EXPECT_EQ(run("bench lodsprite --async --async-lead 0"), 2);
  EXPECT_EQ(run("bench lodsprite --async --async-lead 1.5"), 2);
}

}  // namespace

namespace {

// The trigger comparison finds the contrast threshold that spends the
// geometric trigger's keyframes, and rich shading reaches every renderer
// (full, LOD, sprite), so the report says so and the images change.
TEST(BenchLodsprite, CompareTriggerAndRichShading) {
  tstest::TempDir tmp;
  const fs::path dir = tmp.path;
  const std::string common =
      "bench lodsprite --synthetic-size 65 --resample 65 --frames 16 --size 64x64 --lod-quads 4 "
      "--thresholds 1 --frame-counts 16 --lod-sweep 4 ";
  auto load = [](const fs::path& p) { return nlohmann::json::parse(std::ifstream(p)); };
  ASSERT_EQ(run(common + "--compare-trigger --shading rich --threshold 0.3 --json " +
                (dir / "a.json").string() + " --out " + (dir / "a").string()),
            0);
  ASSERT_EQ(run(common + "--json " + (dir / "b.json").string() + " --out " + (dir / "b").string()),
            0);
  const nlohmann::json a = load(dir / "a.json"), b = load(dir / "b.json");
  EXPECT_EQ(a["shading"], "rich");
  EXPECT_EQ(b["shading"], "plain");
  EXPECT_FALSE(b.contains("trigger_comparison"));
  const nlohmann::json& t = a["trigger_comparison"];
  EXPECT_EQ(t["main"]["metric"], "paper");
  EXPECT_EQ(t["other"]["metric"], "contrast");
  EXPECT_EQ(t["other"]["unit"], "grey levels");
  EXPECT_GT(int(t["simulations"]), 0);
  // Within one keyframe of each other (the counts are a step function of the threshold).
  EXPECT_LE(std::abs(int(t["main"]["keyframes"]) - int(t["other"]["keyframes"])), 1);
  EXPECT_GT(int(t["main"]["keyframes"]), 1);
  for (const char* side : {"main", "other"})
    for (const char* k : {"threshold", "mean_ssim", "mean_psnr", "min_ssim"})
      EXPECT_TRUE(t[side].contains(k)) << side << " " << k;
  // Rich shading changes the full-resolution frames the sprite is scored against.
  std::ifstream fa(dir / "a" / "fig14_full.png", std::ios::binary),
      fb(dir / "b" / "fig14_full.png", std::ios::binary);
  const std::string pa((std::istreambuf_iterator<char>(fa)), {}),
      pb((std::istreambuf_iterator<char>(fb)), {});
  EXPECT_FALSE(pa.empty());
  EXPECT_NE(pa, pb);
  std::ifstream report(dir / "a" / "index.html");
  const std::string html((std::istreambuf_iterator<char>(report)), {});
  EXPECT_NE(html.find("rich terrain shading"), std::string::npos);
  EXPECT_NE(html.find("Keyframe trigger"), std::string::npos);
  // Bad values and combinations: one line, status 2.
  EXPECT_EQ(run(common + "--shading glossy --out " + (dir / "c").string()), 2);
  EXPECT_EQ(run(common + "--compare-trigger --cache --out " + (dir / "c").string()), 2);
  EXPECT_FALSE(fs::exists(dir / "c" / "lodsprite.json"));
}

}  // namespace

namespace {

// Full resolution on one frame in 3 only: sprite and LOD frames all drawn and
// timed, the reference's per-frame figures null between, its total the drawn
// frames' mean x frames, sweeps scored on reference frames. CI cost: ~1 s.
TEST(BenchLodsprite, ReferenceOnEveryNthFrame) {
  tstest::TempDir tmp;
  const std::string json = (tmp.path / "r.json").string(), out = (tmp.path / "report").string();
  ASSERT_EQ(
      run("bench lodsprite --synthetic-size 65 --resample 65 --frames 8 --size 64x64 --lod-quads 4 "
          "--reference-every 3 --sweep-score-every 2 --thresholds 0.5,1 --frame-counts 8 "
          "--lod-sweep 4 --json " +
          json + " --out " + out),
      0);
  const nlohmann::json d = nlohmann::json::parse(std::ifstream(json));
  EXPECT_EQ(d["reference_every"], 3);
  EXPECT_EQ(d["reference_frames"], 3);   // frames 0, 3, 6
  EXPECT_EQ(d["sweep_score_every"], 6);  // lcm(2, 3): sweeps need a reference
  EXPECT_EQ(d["full"]["frames"], 3);
  ASSERT_EQ(d["per_frame"].size(), 8u);
  double full_sum = 0;
  for (const auto& p : d["per_frame"]) {
    const bool ref = int(p["frame"]) % 3 == 0;
    EXPECT_EQ(p["reference"], ref) << p["frame"];
    EXPECT_TRUE(p["ms"].is_number()) << "every sprite frame is timed";
    EXPECT_TRUE(p["lod_ms"].is_number()) << "every LOD frame is timed";
    EXPECT_EQ(p["ssim"].is_number(), ref) << p["frame"];
    EXPECT_EQ(p["lod_ssim"].is_number(), ref) << p["frame"];
    EXPECT_EQ(p["full_ms"].is_number(), ref) << p["frame"];
    if (ref) full_sum += double(p["full_ms"]);
  }
  EXPECT_NEAR(double(d["full"]["total_ms"]), full_sum / 3 * 8, 1e-6 * full_sum + 1e-9);
  EXPECT_EQ(d["full"]["total_ms_method"].get<std::string>().rfind("estimated", 0), 0u);
  EXPECT_EQ(d["sprite"]["keyframes"].get<int>() + d["sprite"]["sprite_frames"].get<int>(), 8);
  std::ifstream report(fs::path(out) / "index.html");
  const std::string html((std::istreambuf_iterator<char>(report)), {});
  EXPECT_NE(html.find("one frame in 3"), std::string::npos);
}

// A bad --reference-every: one line, status 2, no report. CI cost: ~1 s.
TEST(BenchLodsprite, BadReferenceEveryExitsWithStatus2) {
  tstest::TempDir tmp;
  for (const char* bad : {"0", "-4", "x"}) {
    const tstest::CliResult r = tstest::run_cli(std::string("bench lodsprite --reference-every ") +
                                                bad + " --out " + (tmp.path / "o").string());
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << bad << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists(tmp.path / "o" / "lodsprite.json"));
}

}  // namespace
