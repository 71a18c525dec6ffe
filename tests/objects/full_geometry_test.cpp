// SPDX-License-Identifier: MIT
// `objects scene` in-process: two red pyramids on a small synthetic terrain,
// every instance drawn at full geometry and in the picture.
#include "terrasprite/experiment/objects/full_geometry.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "terrasprite/common/stats.h"
#include "terrasprite/report/objects_report.h"
#include "test_util.h"

namespace ts = terrasprite;

TEST(ObjectsFullGeometry, EveryInstanceAtFullGeometryAndInView) {
  tstest::TempDir dir;
  std::ofstream(dir / "pyramid.obj") << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 3 0\n"
                                        "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 3 2\nf 1 4 3\n";
  std::ofstream(dir / "scene.json")
      << R"({"models": [{"name": "p", "file": "pyramid.obj", "height_m": 150, "color": [1, 0, 0]}],
             "instances": [{"model": "p", "position": [0, 0]}, {"model": "p", "position": [300, 200]}]})";
  ts::TerrainOptions to;
  to.synthetic_size = 65;
  const ts::Terrain terrain = ts::load_terrain(to);
  ts::FullGeometryOptions o;
  o.scene = dir / "scene.json";
  o.width = 96;
  o.height = 64;
  o.frames = 2;
  const ts::FullGeometryResult r = ts::run_full_geometry(o, terrain);

  EXPECT_EQ(r.instances, 2u);
  ASSERT_EQ(r.models.size(), 1u);
  EXPECT_EQ(r.models[0].name, "p");
  EXPECT_EQ(r.models[0].triangles, 6u);
  EXPECT_EQ(r.models[0].instances, 2u);
  EXPECT_GE(r.models[0].lod_levels, 1u);
  EXPECT_EQ(r.full_triangles, 12);
  // The full-resolution terrain of 64 x 64 quads, then the same with both pyramids.
  EXPECT_EQ(r.terrain_triangles, 2 * 64 * 64);
  EXPECT_EQ(r.frame_triangles, r.terrain_triangles + r.full_triangles);
  // No cache folder: everything built, nothing counted.
  EXPECT_EQ(r.representation_cache.hits + r.representation_cache.misses, 0);
  // One timed frame each per --frames (the warm-up left out); the median is common/stats'.
  ASSERT_EQ(r.frame_ms.size(), 2u);
  ASSERT_EQ(r.terrain_ms.size(), 2u);
  EXPECT_DOUBLE_EQ(r.median_ms, 0.5 * (r.frame_ms[0] + r.frame_ms[1]));
  EXPECT_DOUBLE_EQ(r.terrain_median_ms, ts::median(r.terrain_ms));
  // Both pyramids framed: red pixels in the picture.
  ASSERT_EQ(r.frame.width, 96);
  ASSERT_EQ(r.frame.height, 64);
  int red = 0;
  for (std::size_t i = 0; i < r.frame.rgba.size(); i += 4)
    red += r.frame.rgba[i] > 2 * r.frame.rgba[i + 1] && r.frame.rgba[i] > 2 * r.frame.rgba[i + 2];
  EXPECT_GT(red, 10);

  const nlohmann::json j = ts::report::full_geometry_json(r);
  EXPECT_EQ(j["size"], nlohmann::json::array({96, 64}));
  EXPECT_EQ(j["frames"], 2);
  EXPECT_EQ(j["models"][0]["lod_levels"], r.models[0].lod_levels);
}
