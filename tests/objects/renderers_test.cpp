// SPDX-License-Identifier: MIT
// Objects in the Scene: the full, LOD and LOD-sprite renderers draw them over
// the terrain, every frame, depth-tested; keyframes stay terrain only.
#include <gtest/gtest.h>

#include <fstream>

#include "object_test_util.h"
#include "terrasprite/gl_context.h"
#include "terrasprite/mesh_renderer.h"
#include "terrasprite/object_set.h"
#include "terrasprite/scene.h"
#include "terrasprite/sprite_renderer.h"
#include "test_util.h"

namespace ts = terrasprite;

namespace {

int differing_pixels(const ts::Image& a, const ts::Image& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4)
    n += a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2];
  return n;
}

struct World {
  tstest::TempDir dir;
  ts::Terrain terrain;
  ts::ObjectScene objects;
  World() {
    ts::TerrainOptions o;
    o.synthetic_size = 65;
    terrain = ts::load_terrain(o);
    std::ofstream(dir / "tower.obj") << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 3 0\n"
                                        "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 3 2\nf 1 4 3\n";
    objects = ts::parse_object_scene(
        R"({"models": [{"name": "t", "file": "tower.obj", "height_m": 150, "color": [1, 0, 0]}],
            "instances": [{"model": "t", "position": [0, 0]}, {"model": "t", "position": [300, 200]}]})",
        "scene", dir.path.string(), terrain.heights);
  }
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
  ts::ObjectSet set(w.objects);
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
  ts::ObjectSet set(w.objects);
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
  EXPECT_EQ(sprite.cls, "sprite");
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
