// SPDX-License-Identifier: MIT
// Scene files: listed and scattered instances on the terrain, bad scenes,
// and the default 400-instance scene.
#include "terrasprite/objects/object_layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/grid_mesh.h"
#include "terrasprite/terrain/terrain.h"
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

// Values out of range, each refused in one line naming the scene file and the
// JSON field, numbers as written (never hundreds of digits, never wrapped).
TEST(ObjectLayout, OutOfRangeValuesNameTheFieldInOneLine) {
  const ts::Heightfield h = ramp();  // 1000 x 1000 m, heights 0..~400 m
  const std::string m = R"({"models": [{"name": "b", "file": "x.obj"}], )";
  const std::pair<std::string, const char*> cases[] = {
      {m + R"("instances": [{"model": "b", "position": [0, 0], "scale": 1e30}]})",
       "bad.json: instances[0].scale 1e+30: must be in [0.001, 1000]"},
      {m + R"("instances": [{"model": "b", "position": [0, 0], "scale": 0}]})",
       "instances[0].scale 0: must be in"},
      {m + R"("instances": [{"model": "b", "position": [0, 0]}, {"model": "b", "position": [1e308, 0]}]})",
       "bad.json: instances[1].position [1e+308, 0]: x and y must be within"},
      {m + R"("instances": [{"model": "b", "position": [-1e308, -1e308]}]})",
       "instances[0].position [-1e+308, -1e+308]"},
      {m + R"("instances": [{"model": "b", "position": [0, 0, 1e308]}]})",
       "instances[0].position z 1e+308: must be within"},
      {m + R"("instances": [{"model": "b", "position": [0, "x"]}]})",
       "instances[0].position: must be [x, y] or [x, y, z] (numbers)"},
      {m + R"("instances": [{"model": 3, "position": [0, 0]}]})",
       "instances[0].model: must be a model's name"},
      {m + R"("instances": {"model": "b"}})", "bad.json: instances: must be an array"},
      {m + R"("scatter": [{"model": "b", "count": 4294967297}]})",
       "bad.json: scatter[0].count 4294967297: must be a whole number in 0..1000000"},
      {m + R"("scatter": [{"model": "b", "count": 1e10}]})",
       "scatter[0].count 10000000000: must be a whole number in 0..1000000"},
      {m + R"("scatter": [{"model": "b", "count": 2.5}]})", "scatter[0].count 2.5"},
      {m + R"("scatter": [{"model": "b", "count": -1}]})", "scatter[0].count -1"},
      {m + R"("scatter": [{"model": "b", "count": 1, "seed": -1}]})", "scatter[0].seed -1"},
      {m + R"("scatter": [{"model": "b", "count": 1, "region": [0, 0, 1e308, 10]}]})",
       "scatter[0].region [0, 0, 1e+308, 10]: empty or leaves the terrain"},
      {m + R"("scatter": [{"model": "b", "count": 1, "max_slope_deg": -5}]})",
       "scatter[0].max_slope_deg -5: must be in [0, 90]"},
      {m + R"("scatter": [{"model": "b", "count": 1, "min_spacing_m": 1e308}]})",
       "scatter[0].min_spacing_m 1e+308: must be in [0, 1000]"},
      {m + R"("scatter_defaults": {"count": 1e10}, "scatter": [{"model": "b"}]})",
       "scatter[0].count 10000000000"},
      {m + R"("instances": [{"model": "b", "position": [0, 0]}],
              "scatter": [{"model": "b", "count": 1000000}]})",
       "scatter[0].count 1000000: the scene would hold more than 1000000 instances"},
      {R"({"models": [{"name": "b", "file": "x.obj", "up": "x"}]})",
       "bad.json: models[0].up (model b): 'x' is not an up axis"},
      {R"({"models": [{"name": "b", "file": "x.obj"}, {"name": "c", "file": "x.obj", "height_m": 1e308}]})",
       "bad.json: models[1].height_m 1e+308: must be in [0, 10000]"},
      {R"({"models": [{"name": "b", "file": "x.obj", "color": [1, 5, 0]}]})",
       "models[0].color value 5: must be in [0, 1]"},
      {R"({"models": [{"file": "x.obj"}]})", "models[0].name: missing"},
      {R"({"models": [{"name": "b", "file": "x.obj"}, {"name": "b", "file": "y.obj"}]})",
       "models[1].name 'b': appears twice"},
      {R"([1, 2])", "bad.json: not a scene file"},
  };
  for (const auto& [text, fragment] : cases) {
    try {
      ts::parse_object_layout(text, "bad.json", ".", h);
      ADD_FAILURE() << text;
    } catch (const ts::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_LT(what.size(), 300u) << what;
    }
  }
}

// Any finite heading is a compass direction, reduced into [0, 360).
TEST(ObjectLayout, HeadingsReduceIntoAFullTurn) {
  const ts::Heightfield h = ramp();
  const ts::ObjectLayout s = ts::parse_object_layout(
      R"({"models": [{"name": "b", "file": "x.obj"}], "instances": [
          {"model": "b", "position": [0, 0], "heading_deg": -90},
          {"model": "b", "position": [0, 0], "heading_deg": 1e308},
          {"model": "b", "position": [0, 0], "heading_deg": 720}]})",
      "t.json", ".", h);
  ASSERT_EQ(s.instances.size(), 3u);
  EXPECT_EQ(s.instances[0].instance.heading_deg, 270.0);
  EXPECT_GE(s.instances[1].instance.heading_deg, 0.0);
  EXPECT_LT(s.instances[1].instance.heading_deg, 360.0);
  EXPECT_EQ(s.instances[2].instance.heading_deg, 0.0);
}

// 100,000 scattered instances keep their spacing from every earlier one
// (a listed instance and a first scatter included); placement compares a
// candidate with its neighbours only, so it ends in well under a second.
TEST(ObjectLayout, AHundredThousandScatteredInstancesKeepTheirSpacing) {
  ts::Heightfield h;
  h.width = h.height = 201;
  h.spacing_x = h.spacing_y = 50;  // 10 x 10 km, flat
  h.heights.assign(201 * 201, 0.0f);
  const ts::ObjectLayout s = ts::parse_object_layout(
      R"({"models": [{"name": "b", "file": "x.obj"}],
          "instances": [{"model": "b", "position": [0, 0]}],
          "scatter": [{"model": "b", "count": 1000, "seed": 1, "min_spacing_m": 20},
                      {"model": "b", "count": 100000, "seed": 2, "min_spacing_m": 10}]})",
      "t.json", ".", h);
  ASSERT_EQ(s.instances.size(), 101001u);
  // Every pair closer than 10 m, found by sorting along x.
  std::vector<glm::dvec2> p;
  for (const auto& i : s.instances) p.emplace_back(i.instance.position);
  std::sort(p.begin(), p.end(), [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x; });
  int close = 0;
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t b = a + 1; b < p.size() && p[b].x - p[a].x < 10; ++b)
      close += glm::length(p[b] - p[a]) < 10;
  EXPECT_EQ(close, 0);
}

// A scatter that cannot place its count says so as soon as its rate shows
// it: a million on slopes no point of the ramp meets ends at once, not after
// its 2e8 attempts; one that fills its region stops once it is full.
TEST(ObjectLayout, AHopelessScatterFailsEarly) {
  const ts::Heightfield h = ramp();
  for (const char* scatter : {R"({"model": "b", "count": 1000000, "max_slope_deg": 1})",
                              R"({"model": "b", "count": 1000000, "min_spacing_m": 10})"}) {
    try {
      ts::parse_object_layout(
          std::string(R"({"models": [{"name": "b", "file": "x.obj"}], "scatter": [)") + scatter +
              "]}",
          "t.json", ".", h);
      ADD_FAILURE() << scatter;
    } catch (const ts::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("t.json: scatter[0] of 'b': placed only"),
                std::string::npos)
          << e.what();
    }
  }
}

// The default scene's placement is fixed by its seed: the same instances
// wherever the spacing test looks them up (first and last of each model).
TEST(ObjectLayout, DefaultScenePlacementIsFixedBySeed) {
  ts::TerrainOptions o;  // the synthetic default terrain; no model file is read
  const ts::Terrain t = ts::load_terrain(o);
  const ts::ObjectLayout s = ts::default_object_layout("/nonexistent", t.heights);
  ASSERT_EQ(s.instances.size(), 400u);
  // What the seed places (a test against every earlier instance places the same).
  const struct {
    std::size_t index;
    int model;
    double x, y, heading;
  } kept[] = {
      {0, 0, -254.97753587538114, -148.0902661111351, 138.2139473216499},
      {3, 0, 227.07355016792144, 160.33376594862494, 245.5292739881821},
      {4, 1, -49.40830363891777, -269.13220578495446, 327.5484057947947},
      {8, 1, 141.00393060181267, 250.30462272698708, 38.522397887516256},
      {9, 2, -217.53777095133825, 211.74632897400835, 243.04357333109022},
      {16, 2, -112.48061689924157, 264.184854816191, 322.95532701972775},
      {17, 3, 44.761210471616096, 219.01839859552888, 331.8184101824301},
      {28, 3, -150.5766631183672, 121.1335309621474, 212.15502082910274},
      {29, 4, 55.92146034126773, 83.9142759981641, 86.35138437163465},
      {88, 4, -77.5893845262957, 261.82118067020485, 82.06427049556056},
      {89, 5, 161.09783687378678, 287.5801848042495, 45.25494771838955},
      {148, 5, -282.25402637152115, -177.473027095552, 339.2580285542756},
      {149, 6, 74.37669712358536, 172.92159496738623, 65.3218764838196},
      {249, 6, -16.777757554707534, 257.08774968785303, 248.02602208485192},
      {250, 7, 234.38902458371774, -112.9286594037732, 293.8858979059161},
      {399, 7, -250.81679563250782, -186.59764683432007, 140.24623590384698},
  };
  for (const auto& k : kept) {
    const ts::PlacedInstance& p = s.instances[k.index];
    EXPECT_EQ(p.model, k.model) << k.index;
    EXPECT_NEAR(p.instance.position.x, k.x, 1e-9) << k.index;
    EXPECT_NEAR(p.instance.position.y, k.y, 1e-9) << k.index;
    EXPECT_NEAR(p.instance.heading_deg, k.heading, 1e-9) << k.index;
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
