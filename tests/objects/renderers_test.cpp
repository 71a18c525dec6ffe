// SPDX-License-Identifier: MIT
// Objects in the Scene: the full, LOD and LOD-sprite renderers draw them over
// the terrain, every frame, depth-tested; keyframes stay terrain only.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/glm.hpp>

#include "object_test_util.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/objects/gl_scene_objects.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/terrain/texture_gen.h"
#include "test_util.h"

namespace ts = terrasprite;
using tstest::tower_layout;

namespace {

int differing_pixels(const ts::Image& a, const ts::Image& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4)
    n += a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2];
  return n;
}

struct World : tstest::TowerWorld {
  World()
      : TowerWorld(
            R"("height_m": 150, "color": [1, 0, 0])",
            R"([{"model": "t", "position": [0, 0]}, {"model": "t", "position": [300, 200]}])") {}
};

ts::Camera view(const ts::Terrain& t) {
  const glm::dvec3 target(0, 0, t.heights.sample(0, 0) + 60);
  ts::Camera c = tstest::orbit(target, 900, 20, 25, 50, 1.0);
  ts::fit_clip_planes(c, t.heights);
  return c;
}

}  // namespace

TEST(SceneObjects, MeshRenderersDrawObjectsOverTheTerrain) {
  ts::GlContext ctx;
  World w;
  ts::Scene scene(w.terrain);
  ts::GlSceneObjects set(w.objects);
  const ts::Camera cam = view(w.terrain);
  for (int quads : {0, 16}) {
    ts::MeshRenderer r(scene, 96, 96, quads);
    scene.set_objects(nullptr);
    const ts::Frame bare = r.render(cam);
    scene.set_objects(&set);
    const ts::Frame with = r.render(cam);
    EXPECT_EQ(with.triangles - bare.triangles, 2 * 6) << quads;
    EXPECT_GT(differing_pixels(bare.color, with.color), 20) << quads;
  }
}

TEST(SceneObjects, SpriteFramesShowObjectsKeyframesHoldTerrainOnly) {
  ts::GlContext ctx;
  World w;
  ts::Scene scene(w.terrain);
  ts::GlSceneObjects set(w.objects);
  ts::Camera cam = view(w.terrain);
  ts::SpriteRenderer bare(scene, 96, 96);
  const ts::Frame bare_key = bare.render_keyframe(cam);
  scene.set_objects(&set);
  ts::SpriteRenderer with(scene, 96, 96);
  const ts::Frame key = with.render_keyframe(cam);
  EXPECT_GT(differing_pixels(bare_key.color, key.color), 20);
  // A sprite frame a little later: the objects are drawn again, not reprojected
  // from the keyframe, so they match a full render of the same view.
  cam.position += glm::dvec3(15, 0, 0);
  const ts::Frame sprite = with.render_sprite(cam);
  EXPECT_EQ(sprite.cls, ts::FrameClass::kSprite);
  ts::MeshRenderer full(scene, 96, 96, 0);
  const ts::Frame reference = full.render(cam);
  int red_sprite = 0, red_full = 0;
  for (std::size_t i = 0; i < sprite.color.rgba.size(); i += 4) {
    red_sprite += sprite.color.rgba[i] > 150 && sprite.color.rgba[i + 1] < 60;
    red_full += reference.color.rgba[i] > 150 && reference.color.rgba[i + 1] < 60;
  }
  EXPECT_GT(red_full, 20);
  EXPECT_NEAR(red_sprite, red_full, red_full / 10 + 3);
}

namespace {

// A flat plain with a 12 m ridge across it; a 30 m red tower stands 55 m
// beyond the ridge, seen from 6 m above the plain: the ridge hides the
// tower's lower part.
struct RidgeWorld {
  tstest::TempDir dir;
  ts::Terrain terrain;
  ts::ObjectLayout objects;
  RidgeWorld() {
    ts::Heightfield& h = terrain.heights;
    h.width = h.height = 65;
    h.spacing_x = h.spacing_y = 10;
    h.heights.assign(std::size_t(h.width) * h.height, 0.f);
    for (int j = 0; j < h.height; ++j)
      for (int i = 0; i < h.width; ++i)
        if (std::abs(h.world_y(j) + 15) <= 5) h.at(i, j) = 12;
    h.name = "ridge";
    terrain.texture = ts::checker_texture(8, 256);
    terrain.texture_name = "checker";
    objects = tower_layout(dir, terrain, R"("height_m": 30, "color": [0, 0, 1])",
                           R"([{"model": "t", "position": [0, 40]}])");
  }
};

// Draws every model of a set as one representation.
struct DrawnAs final : ts::SceneObjects {
  ts::GlSceneObjects& set;
  ts::Representation rep;
  DrawnAs(ts::GlSceneObjects& s, ts::Representation r) : set(s), rep(r) {
    for (std::size_t i = 0; i < set.model_count(); ++i) set.model(i).prepare(rep);
  }
  long long draw(const ts::Camera& c) override {
    std::vector<ts::Representation> reps(set.model_count(), rep);
    return set.draw_with(c, reps);
  }
};

// Rows (top = 0) of the blue tower's pixels: deep blue here and not in the
// terrain-only frame (the checker drape is red and green, the sky pale).
std::pair<int, int> object_rows(const ts::Image& bare, const ts::Image& with) {
  auto blue = [](const ts::Image& im, std::size_t i) {
    return im.rgba[i + 2] > 100 && im.rgba[i] < 60 && im.rgba[i + 1] < 60;
  };
  int top = with.height, bottom = -1;
  for (int y = 0; y < with.height; ++y)
    for (int x = 0; x < with.width; ++x) {
      const std::size_t i = (std::size_t(y) * with.width + x) * 4;
      if (blue(with, i) && !blue(bare, i)) {
        top = std::min(top, y);
        bottom = std::max(bottom, y);
      }
    }
  return {top, bottom};
}

}  // namespace

// An object half hidden behind terrain, as a mesh and as a relief impostor:
// the ridge wins the depth test over the tower's lower part (no object pixel
// below the ridge's crest line) and the upper part shows. Full resolution
// only: a LOD-sprite frame's terrain, and so its occlusion, is its coarse
// mesh's, which does not hold a ridge narrower than one coarse quad.
TEST(SceneObjects, TerrainHidesTheLowerHalfOfAnObjectBehindARidge) {
  ts::GlContext ctx;
  RidgeWorld w;
  ts::Scene scene(w.terrain);
  ts::GlSceneObjects set(w.objects);
  const int size = 128;
  ts::Camera cam = ts::Camera::look_at({0, -200, 6}, {0, 40, 12}, 40, 1.0);
  cam.near_m = 1;
  cam.far_m = 2000;
  // The crest line's image row: the ridge's near top edge (y = -20, z = 12).
  const glm::dvec4 crest = cam.view_projection() * glm::dvec4(0, -20, 12, 1);
  const double crest_row = (1 - crest.y / crest.w) / 2 * size;
  // The tower's top (z = 30 at y = 40) shows well above the crest.
  const glm::dvec4 top = cam.view_projection() * glm::dvec4(0, 40, 30, 1);
  const double top_row = (1 - top.y / top.w) / 2 * size;
  ASSERT_LT(top_row, crest_row - 10);
  for (ts::Representation rep : {ts::Representation{ts::ObjectKind::kMesh},
                                 ts::Representation{ts::ObjectKind::kRelief, 0, 64}}) {
    DrawnAs drawn(set, rep);
    const std::string what = fmt::format("kind {}", int(rep.kind));
    auto frame = [&](ts::SceneObjects* objects) {
      scene.set_objects(objects);
      return ts::MeshRenderer(scene, size, size, 0).render(cam);
    };
    const ts::Frame bare = frame(nullptr), with = frame(&drawn);
    const auto [first, last] = object_rows(bare.color, with.color);
    ASSERT_GE(last, 0) << what << ": the tower's top must show above the ridge";
    EXPECT_LE(first, top_row + 3) << what;
    EXPECT_LE(last, crest_row + 1)
        << what << ": object pixels below the crest at row " << crest_row;
    EXPECT_GT(last, crest_row - 4) << what << ": the tower shows down to the crest";
  }
}
