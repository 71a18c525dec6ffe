// SPDX-License-Identifier: MIT
// `render --objects` and `bench render --objects`: a scene's objects on the
// main commands' frames, and the one-line errors when they cannot be drawn.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "terrasprite/terrain/image_io.h"
#include "terrasprite/common/image.h"
#include "test_util.h"

namespace {

// Twelve red 400 m cubes scattered over a small synthetic terrain.
void write_scene(const tstest::TempDir& dir, const std::string& model_file = "cube.obj") {
  std::ofstream(dir / "cube.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                     "v -1 -1 2\nv 1 -1 2\nv 1 1 2\nv -1 1 2\n"
                                     "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                     "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  std::ofstream(dir / "scene.json") << R"({"models": [{"name": "cube", "file": ")" << model_file
                                    << R"(", "up": "z", "height_m": 400, "color": [1, 0, 0]}],
             "scatter": [{"model": "cube", "count": 12, "seed": 3, "max_slope_deg": 90,
                          "min_spacing_m": 1}]})";
}

int red_pixels(const std::string& png) {
  const terrasprite::Image im = terrasprite::load_image(png);
  int n = 0;
  for (std::size_t i = 0; i + 3 < im.rgba.size(); i += 4)
    n += im.rgba[i] > 120 && im.rgba[i + 1] < 40 && im.rgba[i + 2] < 40;
  return n;
}

const std::string kSmall = " --synthetic-size 129 --frames 1 --size 96x96";

}  // namespace

TEST(RenderObjects, SceneFileDrawsObjects) {
  tstest::TempDir dir;
  write_scene(dir);
  // Full only: the sprite and LOD renderers draw Scene objects in SceneObjects.*.
  for (const char* mode : {"full"}) {
    const std::string m = std::string(" --mode ") + mode;
    const auto with = tstest::run_cli("render" + kSmall + m + " --objects " + (dir / "scene.json") +
                                      " --out " + (dir / (std::string("with_") + mode)));
    ASSERT_EQ(with.status, 0) << with.output;
    const auto without = tstest::run_cli("render" + kSmall + m + " --out " +
                                         (dir / (std::string("without_") + mode)));
    ASSERT_EQ(without.status, 0) << without.output;
    EXPECT_GT(red_pixels(dir / (std::string("with_") + mode + "/frame_0000.png")), 50) << mode;
    EXPECT_EQ(red_pixels(dir / (std::string("without_") + mode + "/frame_0000.png")), 0) << mode;
  }
  const auto bench = tstest::run_cli("bench render" + kSmall + " --objects " +
                                     (dir / "scene.json") + " --json " + (dir / "bench.json"));
  ASSERT_EQ(bench.status, 0) << bench.output;
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir / "bench.json"))["objects"], 12);
}

TEST(RenderObjects, MissingModelOrCpuModeIsOneLineExit2) {
  tstest::TempDir dir;
  write_scene(dir, "absent.obj");
  const auto missing = tstest::run_cli("render" + kSmall + " --objects " + (dir / "scene.json") +
                                       " --out " + (dir / "a"));
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find("absent.obj"), std::string::npos) << missing.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "a"));
  const auto defaults = tstest::run_cli("render" + kSmall + " --objects default --models-dir " +
                                        (dir / "nothing_here") + " --out " + (dir / "b"));
  EXPECT_EQ(defaults.status, 2) << defaults.output;
  EXPECT_NE(defaults.output.find("--models-dir"), std::string::npos) << defaults.output;
  EXPECT_EQ(std::count(defaults.output.begin(), defaults.output.end(), '\n'), 1) << defaults.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "b"));
  write_scene(dir);
  const auto voxel = tstest::run_cli("render" + kSmall + " --mode voxel --objects " +
                                     (dir / "scene.json") + " --out " + (dir / "c"));
  EXPECT_EQ(voxel.status, 2) << voxel.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "c"));
}
