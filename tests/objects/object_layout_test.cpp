// SPDX-License-Identifier: MIT
// Scene files: listed and scattered instances on the terrain, bad scenes,
// and the default 400-instance scene.
#include "terrasprite/objects/object_layout.h"

#include <gtest/gtest.h>

#include <fstream>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/terrain/grid_mesh.h"
#include "test_util.h"

namespace ts = terrasprite;

namespace {

// A 101 x 101 grid, 10 m spacing, a ramp rising 1 m per 10 m eastwards
// (5.7 degrees) with a 60-degree cliff band east of x = 300.
ts::Heightfield ramp() {
  ts::Heightfield h;
  h.width = h.height = 101;
  h.spacing_x = h.spacing_y = 10;
  h.heights.resize(101 * 101);
  for (int j = 0; j < 101; ++j)
    for (int i = 0; i < 101; ++i) {
      const double x = h.world_x(i);
      h.at(i, j) = float(0.1 * x + (x > 300 ? (x - 300) * 1.7 : 0.0));
    }
  return h;
}

}  // namespace

TEST(ObjectLayout, ListedAndScatteredInstancesStandOnTheGround) {
  tstest::TempDir dir;
  std::ofstream(dir / "box.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const ts::Heightfield h = ramp();
  const std::string text = R"({"models": [{"name": "b", "file": "box.obj", "height_m": 2}],
    "instances": [{"model": "b", "position": [100, 50], "heading_deg": 90},
                  {"model": "b", "position": [0, 0, 42], "scale": 2}],
    "scatter": [{"model": "b", "count": 30, "seed": 3, "region": [-400, -400, 450, 400],
                 "max_slope_deg": 20, "min_spacing_m": 25}]})";
  const ts::ObjectLayout s = ts::parse_object_layout(text, "t.json", dir.path.string(), h);
  ASSERT_EQ(s.models.size(), 1u);
  EXPECT_EQ(s.models[0].options.height_m, 2.0);
  ASSERT_EQ(s.instances.size(), 32u);
  EXPECT_NEAR(s.instances[0].instance.position.z, 10.0, 1e-4);  // on the ramp
  EXPECT_EQ(s.instances[0].instance.heading_deg, 90.0);
  EXPECT_EQ(s.instances[1].instance.position.z, 42.0);
  const auto drawn = ts::grid_surface(h, 0);
  for (std::size_t a = 2; a < s.instances.size(); ++a) {
    const glm::dvec3 p = s.instances[a].instance.position;
    EXPECT_LE(p.x, 300.0 + 10.0) << "on the cliff";
    EXPECT_NEAR(p.z, drawn(p.x, p.y), 1e-4);
    for (std::size_t b = 0; b < a; ++b)
      EXPECT_GE(glm::length(glm::dvec2(p) - glm::dvec2(s.instances[b].instance.position)), 25.0);
  }
  // The same seed places the same instances.
  const ts::ObjectLayout again = ts::parse_object_layout(text, "t.json", dir.path.string(), h);
  EXPECT_EQ(again.instances.back().instance.position, s.instances.back().instance.position);
}

// A saddle: inside a quad the bilinear surface and the drawn triangles part
// (by 25 m at the centre of this 10 m quad). Instances stand on the triangles.
TEST(ObjectLayout, InstancesStandOnTheDrawnTrianglesNotTheBilinearSurface) {
  tstest::TempDir dir;
  std::ofstream(dir / "box.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  ts::Heightfield h;
  h.width = h.height = 2;
  h.spacing_x = h.spacing_y = 10;
  h.heights = {100, 0, 0, 0};  // NW high, the rest low
  const std::string text = R"({"models": [{"name": "b", "file": "box.obj"}],
    "instances": [{"model": "b", "position": [0, 0]}, {"model": "b", "position": [-2.5, -2]}]})";
  const ts::ObjectLayout s = ts::parse_object_layout(text, "t.json", dir.path.string(), h);
  ASSERT_EQ(s.instances.size(), 2u);
  // The centre lies on the NW-SE diagonal: (100 + 0) / 2 on the triangles,
  // 25 on the bilinear surface.
  EXPECT_NEAR(h.sample(0, 0), 25.0, 1e-6);
  EXPECT_NEAR(s.instances[0].instance.position.z, 50.0, 1e-6);
  // South of the diagonal, in triangle (NW, SW, SE): u = 0.25, v = 0.7, so
  // 100 - 0.7 * 100 = 30 on the triangles; (0.75 * 0.3) * 100 = 22.5 bilinear.
  EXPECT_NEAR(h.sample(-2.5, -2), 22.5, 1e-6);
  EXPECT_NEAR(s.instances[1].instance.position.z, 30.0, 1e-6);
}

TEST(ObjectLayout, BadScenesNameTheFile) {
  const ts::Heightfield h = ramp();
  for (
      const char* text : {
          "{",  // not JSON
          R"({"models": []})",
          R"({"models": [{"name": "b", "file": "x.obj"}], "instances": [{"model": "c", "position": [0, 0]}]})",
          R"({"models": [{"name": "b", "file": "x.obj"}], "scatter": [{"model": "b", "count": 5, "region": [0, 0, 9000, 10]}]})",
          R"({"models": [{"name": "b", "file": "x.obj"}], "scatter": [{"model": "b", "count": 500, "region": [0, 0, 50, 50], "min_spacing_m": 20}]})",
      }) {
    try {
      ts::parse_object_layout(text, "bad.json", ".", h);
      ADD_FAILURE() << text;
    } catch (const ts::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
  }
}

TEST(ObjectLayout, DefaultSceneHas400InstancesOf8Models) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  ts::TerrainOptions o;  // the synthetic default terrain
  const ts::Terrain t = ts::load_terrain(o);
  const ts::ObjectLayout s = ts::default_object_layout(data, t.heights);
  EXPECT_EQ(s.models.size(), 8u);
  EXPECT_EQ(s.instances.size(), 400u);
  std::vector<long long> tris;
  for (const ts::LayoutModel& m : s.models)
    tris.push_back((long long)ts::load_model(m.file, m.options).triangles());
  long long total = 0;
  std::vector<int> count(s.models.size());
  for (const ts::PlacedInstance& p : s.instances) {
    total += tris[p.model];
    ++count[p.model];
  }
  EXPECT_GE(total, 1500000);
  EXPECT_LT(count[0], count[4]) << "fewer bunnies than teapots";
}
