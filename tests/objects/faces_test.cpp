// SPDX-License-Identifier: MIT
// Single- and double-sided materials: which meshes may lose their back
// faces, what the loaders and scene files say, and that drawing without
// them changes nothing seen from outside a closed mesh or from above one
// whose openings face down.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "gl/render_target.h"
#include "object_test_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/object_renderer.h"
#include "terrasprite/quality/quality.h"

namespace ts = terrasprite;

namespace {

// A unit cube as an OBJ, counter-clockwise from outside; `faces` of its six
// quads written (the first n), `inverted` winds every one the other way.
std::string cube_obj(int faces = 6, bool inverted = false) {
  std::string s =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 "
      "1\nv 0 1 1\n";
  const char* quads[6] = {"1 4 3 2", "5 6 7 8", "1 2 6 5", "2 3 7 6", "3 4 8 7", "4 1 5 8"};
  for (int f = 0; f < faces; ++f) {
    std::string q = quads[f];
    if (inverted) q = std::string(q.rbegin(), q.rend());
    s += "f " + q + "\n";
  }
  return s;
}

// colored_box (double-sided) without face `f` (+x, -x, +y, -y, +z, -z).
ts::Model box_without(int f) {
  ts::Model m = tstest::colored_box();
  const ts::MeshPart gone = m.parts[f];
  m.indices.erase(m.indices.begin() + gone.first_index,
                  m.indices.begin() + gone.first_index + gone.index_count);
  m.parts.erase(m.parts.begin() + f);
  for (ts::MeshPart& p : m.parts)
    if (p.first_index > gone.first_index) p.first_index -= gone.index_count;
  return m;
}

bool all_double_sided(const ts::Model& m, bool value) {
  for (const ts::Material& mat : m.materials)
    if (mat.double_sided != value) return false;
  return true;
}

}  // namespace

TEST(Faces, ClosedAndOutwardNeedsEveryEdgePairedAndPositiveVolume) {
  // colored_box has four copies of each corner (a flat normal per face):
  // they weld into one.
  ts::Model box = tstest::colored_box();
  EXPECT_TRUE(ts::closed_and_outward(box.positions, box.indices));

  std::vector<std::uint32_t> inside_out = box.indices;
  for (std::size_t t = 0; t < inside_out.size(); t += 3)
    std::swap(inside_out[t + 1], inside_out[t + 2]);
  EXPECT_FALSE(ts::closed_and_outward(box.positions, inside_out));  // closed, volume < 0

  std::vector<std::uint32_t> one_flipped = box.indices;
  std::swap(one_flipped[1], one_flipped[2]);
  EXPECT_FALSE(ts::closed_and_outward(box.positions, one_flipped));

  std::vector<std::uint32_t> open(box.indices.begin(),
                                  box.indices.end() - 6);  // one face off
  EXPECT_FALSE(ts::closed_and_outward(box.positions, open));

  // A degenerate triangle (two corners at one spot) is ignored.
  std::vector<std::uint32_t> with_sliver = box.indices;
  with_sliver.insert(with_sliver.end(), {0, 0, 1});
  EXPECT_TRUE(ts::closed_and_outward(box.positions, with_sliver));

  EXPECT_FALSE(ts::closed_and_outward(box.positions, {}));
}

TEST(Faces, ObjIsSingleSidedOnlyWhenClosedAndOutward) {
  tstest::TempDir dir;
  std::ofstream(dir / "cube.obj") << cube_obj();
  std::ofstream(dir / "open.obj") << cube_obj(5);
  std::ofstream(dir / "inverted.obj") << cube_obj(6, true);
  EXPECT_TRUE(all_double_sided(ts::load_model(dir / "cube.obj"), false));
  EXPECT_TRUE(all_double_sided(ts::load_model(dir / "open.obj"), true));
  EXPECT_TRUE(all_double_sided(ts::load_model(dir / "inverted.obj"), true));
  // The y-up to z-up turn is a rotation: it keeps the winding.
  ts::ModelOptions z_up;
  z_up.up = ts::UpAxis::kZ;
  EXPECT_TRUE(all_double_sided(ts::load_model(dir / "cube.obj", z_up), false));
  // The scene's word overrides either way.
  ts::ModelOptions both, single;
  both.double_sided = true;
  single.double_sided = false;
  EXPECT_TRUE(all_double_sided(ts::load_model(dir / "cube.obj", both), true));
  EXPECT_TRUE(all_double_sided(ts::load_model(dir / "open.obj", single), false));
}

TEST(Faces, GltfMaterialsSayForThemselves) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  // Every material of the truck leaves doubleSided at its default (false);
  // the Kenney forest's one material sets it (its leaves are cards).
  const ts::Model truck = ts::load_model(data + "/models_cesium_milk_truck/CesiumMilkTruck.glb");
  EXPECT_TRUE(all_double_sided(truck, false));
  const ts::Model forest = ts::load_model(data + "/models_kenney_racing/decoration-forest.glb");
  const ts::Material& leaves = forest.materials[forest.parts[0].material];
  EXPECT_TRUE(leaves.double_sided);
  // Scans: spot is closed; the bunny has holes in its base.
  EXPECT_TRUE(all_double_sided(ts::load_model(data + "/models_scans/spot.obj"), false));
  EXPECT_TRUE(all_double_sided(ts::load_model(data + "/models_scans/stanford-bunny.obj"), true));
}

TEST(Faces, SceneFileDoubleSidedIsABoolean) {
  ts::TerrainOptions o;
  o.synthetic_size = 33;
  const ts::Terrain terrain = ts::load_terrain(o);
  tstest::TempDir dir;
  const ts::ObjectLayout scene =
      tstest::tower_layout(dir, terrain, R"("double_sided": false)", "[]");
  ASSERT_EQ(scene.models.size(), 1u);
  ASSERT_TRUE(scene.models[0].options.double_sided.has_value());
  EXPECT_FALSE(*scene.models[0].options.double_sided);
  try {
    tstest::tower_layout(dir, terrain, R"("double_sided": "yes")", "[]");
    ADD_FAILURE() << "a string was taken";
  } catch (const ts::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("double_sided"), std::string::npos) << e.what();
  }
}

// Seen from outside, a closed outward box looks the same with or without its
// back faces; from inside, a single-sided box is not there at all.
TEST(Faces, BackFacesAreSkippedAndInvisibleFromOutside) {
  ts::GlContext ctx;
  ts::gl::RenderTarget target(96, 96);
  ts::Model single = tstest::colored_box();
  for (ts::Material& m : single.materials) m.double_sided = false;
  const ts::Model both = tstest::colored_box();
  ts::GlModel gl_single(single, ts::build_lod_chain(single)),
      gl_both(both, ts::build_lod_chain(both));
  const ts::ObjectInstance at_origin;
  const ts::Representation mesh{ts::ObjectKind::kMesh};
  auto shot = [&](ts::GlModel& m, const ts::Camera& cam) {
    target.bind_and_clear();
    m.draw(mesh, std::span(&at_origin, 1), cam);
    glFinish();
    return target.read_color();
  };
  for (double phi : {0.0, 50.0, 135.0, 250.0}) {
    const ts::Camera outside = tstest::orbit({0, 0, 0.5}, 4.0, phi, 25.0);
    const ts::Image a = shot(gl_both, outside), b = shot(gl_single, outside);
    EXPECT_EQ(a.rgba, b.rgba) << "phi " << phi;
  }
  ts::Camera inside = tstest::orbit({0, 0, 0.5}, 0.2, 30.0, 10.0, 60.0);
  inside.near_m = 0.01;
  inside.far_m = 10;
  const ts::Image walls = shot(gl_both, inside), none = shot(gl_single, inside);
  target.bind_and_clear();
  glFinish();
  const ts::Image empty = target.read_color();
  EXPECT_NE(walls.rgba, empty.rgba);
  EXPECT_EQ(none.rgba, empty.rgba);
}

// A quad modelled twice, the second wound the other way with its normal
// reversed, and a lone triangle, all in one double-sided material: the
// pair's four triangles go to a single-sided copy of it, and the model
// looks from every side as the quad alone, double-sided, does.
TEST(Faces, OppositeTwinsAreDrawnSingleSidedAndLookTheSame) {
  tstest::TempDir dir;
  const std::string vertices =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv "
      "3 0 0\nv 2 1 0\nvn 0 0 1\nvn 0 0 -1\n";
  const std::string quad = "f 1//1 2//1 3//1 4//1\n", lone = "f 5//1 6//1 7//1\n";
  std::ofstream(dir / "once.obj") << vertices << quad << lone;
  // The other side starts at 3: the fan then splits it on the same diagonal.
  std::ofstream(dir / "twice.obj") << vertices << quad << "f 3//2 2//2 1//2 4//2\n"
                                   << lone
                                   // the same winding again is not the other side
                                   << "f 5//1 6//1 7//1\n";
  const ts::Model once = ts::load_model(dir / "once.obj"),
                  twice = ts::load_model(dir / "twice.obj");
  ASSERT_EQ(once.materials.size(), 1u);
  ASSERT_EQ(twice.materials.size(), 2u);
  EXPECT_TRUE(twice.materials[0].double_sided);
  EXPECT_FALSE(twice.materials[1].double_sided);
  EXPECT_NE(twice.materials[1].name.find("one side each"), std::string::npos);
  ASSERT_EQ(twice.parts.size(), 2u);
  EXPECT_EQ(twice.parts[0].index_count, 6u);   // the lone triangle, twice
  EXPECT_EQ(twice.parts[1].index_count, 12u);  // the quad's two sides

  ts::GlContext ctx;
  ts::gl::RenderTarget target(96, 96);
  ts::GlModel gl_once(once, ts::build_lod_chain(once)), gl_twice(twice, ts::build_lod_chain(twice));
  const ts::ObjectInstance at_origin;
  const ts::Representation mesh{ts::ObjectKind::kMesh};
  auto shot = [&](ts::GlModel& m, const ts::Camera& cam) {
    target.bind_and_clear();
    m.draw(mesh, std::span(&at_origin, 1), cam);
    return target.read_color();
  };
  for (double phi : {20.0, 160.0, 200.0, 340.0})
    for (double elev : {10.0, 60.0}) {
      const ts::Camera cam = tstest::orbit({0, 0, 0.5}, 6.0, phi, elev);
      const ts::Image a = shot(gl_once, cam), b = shot(gl_twice, cam);
      EXPECT_GT(ts::quality::ssim(a.view(), b.view()).ssim, 0.999)
          << "phi " << phi << " elev " << elev;
    }
}

// The forest's paired triangles, drawn single-sided, look as they did when
// both of every pair were drawn double-sided, from above and from under the
// treetops.
TEST(Faces, ForestLooksTheSameWithItsTwinsSingleSided) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  const ts::Model forest = tstest::forest_10m(data);
  long long single_sided = 0;
  for (const ts::MeshPart& p : forest.parts)
    if (!forest.materials[std::size_t(p.material)].double_sided) single_sided += p.index_count / 3;
  EXPECT_EQ(single_sided, 756);
  ts::Model both = forest;
  for (ts::Material& m : both.materials) m.double_sided = true;
  ts::GlContext ctx;
  ts::gl::RenderTarget target(160, 90);
  auto level0 = [](const ts::Model& m) {
    std::vector<ts::LodLevel> chain = ts::build_lod_chain(m);
    chain.resize(1);  // the simplification is not under test
    return chain;
  };
  ts::GlModel gl(forest, level0(forest)), gl_both(both, level0(both));
  gl.set_cull_hidden_back_faces(false);
  gl_both.set_cull_hidden_back_faces(false);
  const ts::ObjectInstance at_origin;
  const ts::Representation mesh{ts::ObjectKind::kMesh};
  target.bind_and_clear();
  const ts::Image empty = target.read_color();
  for (double elev : {-5.0, 5.0, 30.0, 70.0})
    for (double phi : {0.0, 100.0, 230.0}) {
      const ts::Camera cam = tstest::orbit({0, 0, 5}, 30.0, phi, elev, 50.0, 16.0 / 9.0);
      ts::Image shots[2];
      int k = 0;
      for (ts::GlModel* m : {&gl, &gl_both}) {
        target.bind_and_clear();
        m->draw(mesh, std::span(&at_origin, 1), cam);
        shots[k++] = target.read_color();
      }
      EXPECT_NE(shots[0].rgba, empty.rgba);
      EXPECT_GT(ts::quality::ssim(shots[0].view(), shots[1].view()).ssim, 0.999)
          << "elev " << elev << " phi " << phi;
    }
}

// From above its top, a double-sided model loses its back faces only where
// none can show: a closed box and one open underneath (a tree) do, a box open
// on top (a cup) does not. What is seen stays the same either way, and the
// culling is real: fewer fragments are shaded.
TEST(Faces, BackFacesAreCulledFromAboveOnlyWhereNoneShows) {
  ts::GlContext ctx;
  ts::gl::RenderTarget target(96, 96);
  const ts::Model closed = tstest::colored_box(), open_below = box_without(5), cup = box_without(4);
  ts::GlModel gl_closed(closed, ts::build_lod_chain(closed)),
      gl_open_below(open_below, ts::build_lod_chain(open_below)),
      gl_cup(cup, ts::build_lod_chain(cup));
  EXPECT_EQ(gl_closed.back_faces_hidden_above(0), 1.0);  // the box's top, metres
  EXPECT_EQ(gl_open_below.back_faces_hidden_above(0), 1.0);
  EXPECT_TRUE(std::isinf(gl_cup.back_faces_hidden_above(0)));

  const ts::ObjectInstance at_origin;
  const ts::Representation mesh{ts::ObjectKind::kMesh};
  GLuint query = 0;
  glGenQueries(1, &query);
  auto shot = [&](ts::GlModel& m, const ts::Camera& cam, bool cull, GLuint* fragments) {
    m.set_cull_hidden_back_faces(cull);
    target.bind_and_clear();
    glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, query);
    m.draw(mesh, std::span(&at_origin, 1), cam);
    glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
    glGetQueryObjectuiv(query, GL_QUERY_RESULT, fragments);
    return target.read_color();
  };
  for (ts::GlModel* m : {&gl_closed, &gl_open_below, &gl_cup}) {
    for (double phi : {0.0, 130.0}) {
      // 4 m out at 40 degrees: 3 m above the box's top.
      const ts::Camera above = tstest::orbit({0, 0, 0.5}, 4.0, phi, 40.0);
      GLuint both = 0, culled = 0;
      const ts::Image a = shot(*m, above, false, &both), b = shot(*m, above, true, &culled);
      EXPECT_EQ(a.rgba, b.rgba) << m->model().name << " phi " << phi;
      if (m == &gl_cup)
        EXPECT_EQ(culled, both);
      else
        EXPECT_LT(culled, both) << "phi " << phi;  // the far walls' insides
      // Beside the box, under its top: its back faces are drawn as before.
      const ts::Camera beside = tstest::orbit({0, 0, 0.5}, 4.0, phi, 3.0);
      shot(*m, beside, false, &both);
      shot(*m, beside, true, &culled);
      EXPECT_EQ(culled, both) << "phi " << phi;
    }
  }
  glDeleteQueries(1, &query);

  // The same answer as the cost model asks it, per instance: the camera
  // (3.07 m up) above the box's top times the instance's scale, on its base.
  const ts::Camera above = tstest::orbit({0, 0, 0.5}, 4.0, 0.0, 40.0),
                   beside = tstest::orbit({0, 0, 0.5}, 4.0, 0.0, 3.0);
  ts::ObjectInstance raised, tall;
  raised.position.z = 2.5;
  tall.scale = 4;
  gl_open_below.set_cull_hidden_back_faces(true);
  EXPECT_TRUE(gl_open_below.culls_back_faces(mesh, at_origin, above));
  EXPECT_FALSE(gl_open_below.culls_back_faces(mesh, at_origin, beside));
  EXPECT_FALSE(gl_open_below.culls_back_faces(mesh, raised, above));
  EXPECT_FALSE(gl_open_below.culls_back_faces(mesh, tall, above));
  EXPECT_FALSE(gl_open_below.culls_back_faces({ts::ObjectKind::kRelief}, at_origin, above));
  gl_cup.set_cull_hidden_back_faces(true);
  EXPECT_FALSE(gl_cup.culls_back_faces(mesh, at_origin, above));
  gl_open_below.set_cull_hidden_back_faces(false);
  EXPECT_FALSE(gl_open_below.culls_back_faces(mesh, at_origin, above));
}

// The default scene's forest: its full level qualifies, and from above it
// looks the same without back faces (its cards' backs face down).
TEST(Faces, ForestSeenFromAboveLooksTheSameWithoutBackFaces) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  ts::GlContext ctx;
  ts::gl::RenderTarget target(160, 90);
  const ts::Model forest = tstest::forest_10m(data);
  std::vector<ts::LodLevel> chain = ts::build_lod_chain(forest);
  chain.resize(1);  // level 0 only: the simplification is not under test
  ts::GlModel gl(forest, std::move(chain));
  EXPECT_NEAR(gl.back_faces_hidden_above(0), 10.0, 1e-4);
  std::vector<ts::ObjectInstance> grid;
  for (int i = 0; i < 12; ++i)
    grid.push_back({{(i % 4 - 1.5) * 30.0, (i / 4 - 1.0) * 30.0, 0.0}, 37.0 * i, 1.0});
  const ts::Representation mesh{ts::ObjectKind::kMesh};
  for (double elev : {8.0, 35.0}) {
    ts::Camera cam = tstest::orbit({0, 0, 0}, 180.0, 20.0, elev, 40.0, 16.0 / 9.0);
    ts::Image shots[2];
    for (int cull = 0; cull < 2; ++cull) {
      gl.set_cull_hidden_back_faces(cull == 1);
      target.bind_and_clear();
      gl.draw(mesh, grid, cam);
      shots[cull] = target.read_color();
    }
    EXPECT_GT(ts::quality::ssim(shots[0].view(), shots[1].view()).ssim, 0.999) << "elev " << elev;
  }
}

// Within one draw of several groups, the instances the camera is above are
// moved first and drawn culled, the rest as before: every instance must
// still be drawn once, where it stands, whichever side of the line it is on.
TEST(Faces, GroupsMixingInstancesAboveAndBelowTheCameraDrawEveryInstance) {
  ts::GlContext ctx;
  ts::gl::RenderTarget target(128, 96);
  const ts::Model open_below = box_without(5);
  ts::GlModel gl(open_below, ts::build_lod_chain(open_below));
  ASSERT_EQ(gl.back_faces_hidden_above(0), 1.0);
  // Boxes 1 m tall on a slope: the camera at z = 2 is above those based
  // below z = 1 and under the others, alternating along the row.
  std::vector<ts::ObjectInstance> first, second;
  for (int i = 0; i < 8; ++i) {
    const ts::ObjectInstance o{{-7.0 + 2.0 * i, 6.0, i % 2 == 0 ? 0.5 : 1.8}, 20.0 * i, 0.8};
    (i < 5 ? first : second).push_back(o);
  }
  const ts::Representation mesh{ts::ObjectKind::kMesh};
  const ts::GlModel::Group groups[2] = {{mesh, first}, {mesh, second}};
  ts::Camera cam = ts::Camera::look_at({0, -4, 2}, {0, 6, 1}, 70.0, 128.0 / 96.0);
  cam.near_m = 0.1;
  cam.far_m = 100;
  ts::Image shots[2];
  for (int cull = 0; cull < 2; ++cull) {
    gl.set_cull_hidden_back_faces(cull == 1);
    target.bind_and_clear();
    gl.draw(groups, cam);
    shots[cull] = target.read_color();
  }
  EXPECT_EQ(shots[0].rgba, shots[1].rgba);
  // And every box is there: the pixel at its centre is not the sky's.
  target.bind_and_clear();
  const ts::Image sky = target.read_color();
  for (const auto* group : {&first, &second})
    for (const ts::ObjectInstance& o : *group) {
      const glm::dvec4 c =
          cam.view_projection() * glm::dvec4(o.position + glm::dvec3(0, 0, 0.4), 1);
      const int x = int((c.x / c.w + 1) / 2 * 128), y = int((1 - c.y / c.w) / 2 * 96);
      ASSERT_TRUE(x >= 0 && x < 128 && y >= 0 && y < 96) << o.position.x;
      const std::size_t at = (std::size_t(y) * 128 + std::size_t(x)) * 4;
      EXPECT_NE(std::memcmp(&shots[1].rgba[at], &sky.rgba[at], 3), 0)
          << "box at x " << o.position.x;
    }
}
