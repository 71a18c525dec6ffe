// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/terrain/grid_mesh.h"
#include "terrasprite/hybrid/walkthrough_path.h"

namespace terrasprite {
namespace {

constexpr const char* kPath =
    R"({"keyframes": [{"t": 1, "position": [0, 0, 5], "yaw_deg": 0},
                  {"t": 11, "position": [9, 0, 5], "yaw_deg": 0}],
  "checkpoints": [{"name": "A", "t": 1}, {"name": "B", "t": 6}, {"name": "C", "t": 11}]})";

TEST(Walkthrough, CheckpointsLandOnTheirFrames) {
  const auto cps = checkpoint_frames(parse_path_json(kPath, "p.json"), 21);
  ASSERT_EQ(cps.size(), 3u);
  EXPECT_EQ(cps[0].frame, 0);
  EXPECT_EQ(cps[1].frame, 10);
  EXPECT_EQ(cps[2].frame, 20);
  EXPECT_TRUE(checkpoint_frames(parse_path_json(R"({"keyframes": [{"t": 0, "position": [0, 0, 5],
                                  "yaw_deg": 0}]})",
                                                "p.json"),
                                5)
                  .empty());
}

TEST(Walkthrough, BadCheckpointsNameTheFileAndTheCheckpoint) {
  const std::string keys =
      R"("keyframes": [{"t": 0, "position": [0, 0, 5], "yaw_deg": 0},
                       {"t": 1, "position": [9, 0, 5], "yaw_deg": 0}])";
  for (const std::string bad : {R"("checkpoints": [{"t": 0.5}])",
                                R"("checkpoints": [{"name": "A", "t": 2}])",
                                R"("checkpoints": [{"name": "A", "t": "x"}])",
                                R"("checkpoints": 3)"}) {
    try {
      parse_path_json("{" + keys + ", " + bad + "}", "p.json");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("p.json: ", 0), 0u) << what;
      EXPECT_NE(what.find("checkpoints"), std::string::npos) << what;
    }
  }
}

// The default walkthrough as data samples to the cameras its path-file
// JSON gives: the same keyframes, checkpoints A-E.
TEST(Walkthrough, DefaultPathIsAPathFile) {
  const Terrain t = load_terrain(TerrainOptions{});
  const KeyframePath p = walkthrough_path(t.heights);
  ASSERT_EQ(p.keyframes.size(), 9u);
  ASSERT_EQ(p.checkpoints.size(), 5u);
  EXPECT_EQ(p.checkpoints.front().name, "A");
  EXPECT_EQ(p.checkpoints.back().name, "E");
  std::string json = R"({"keyframes": [)";
  for (const PathKeyframe& k : p.keyframes)
    json += fmt::format(R"({}{{"t": {}, "position": [{}, {}, {}], "target": [{}, {}, {}]}})",
                        &k == &p.keyframes.front() ? "" : ", ", k.t, k.position.x, k.position.y,
                        k.position.z, k.target->x, k.target->y, k.target->z);
  json += "]}";
  const auto a = sample_path(p, t.heights, 40, 16.0 / 9);
  const auto b = path_from_json(json, "walkthrough", t.heights, 40, 16.0 / 9);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position) << "frame " << i;
    EXPECT_EQ(a[i].yaw_deg, b[i].yaw_deg) << "frame " << i;
    EXPECT_EQ(a[i].pitch_deg, b[i].pitch_deg) << "frame " << i;
  }
}

// The default walkthrough over the terrain as the bench draws it (the
// synthetic terrain's 64-quad grid): every frame's eye is over the drawn
// surface, so no frame sees a face of it from below. Checked by drawing each
// frame with the back faces culled and with them: before the walkthrough
// stood on the drawn grid, 108 of its 160 frames differed in 72-93% of
// their pixels. About 1 s of CI (320 renders of 8192 triangles at 160 x 90).
TEST(Walkthrough, NeverSeesTheDrawnTerrainFromBelow) {
  GlContext gl;
  const Terrain t = load_terrain(TerrainOptions{});
  const Heightfield& hf = t.heights;
  const int quads = 64, w = 160, h = 90;
  const auto drawn = grid_surface(hf, quads);
  std::vector<Camera> path = sample_path(walkthrough_path(hf, drawn), hf, 160, double(w) / h);
  keep_above_ground(path, drawn);
  Scene scene(t);
  MeshRenderer culled(scene, w, h, quads, RasterOptions{.cull_back_faces = true}),
      all(scene, w, h, quads);
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Camera& c = path[i];
    ASSERT_GE(c.position.z - drawn(c.position.x, c.position.y), 1.5 - 1e-9) << "frame " << i;
    const Frame a = culled.render(c, ReadBack::kColorDepth);
    const Frame b = all.render(c, ReadBack::kColorDepth);
    std::size_t differ = 0;
    for (std::size_t k = 0; k < a.color.rgba.size(); k += 4)
      differ += !std::equal(&a.color.rgba[k], &a.color.rgba[k] + 3, &b.color.rgba[k]);
    // Seen from below, most of the image differs (72-93% of it in the
    // frames that did); along a ridge's silhouette the face behind may take
    // a pixel on the shared edge (1 pixel in 11 of the 160 frames).
    EXPECT_LE(differ, std::size_t(w * h / 1000)) << "frame " << i << ": pixels that differ";
  }
}

TEST(Walkthrough, KeepAboveGroundRaisesAndRefitsTheNearPlane) {
  Camera low, high;
  low.position = {0, 0, 1.0};
  low.near_m = 5;
  high.position = {0, 0, 40.0};
  high.near_m = 2;
  std::vector<Camera> p = {low, high};
  keep_above_ground(p, [](double, double) { return 10.0; });
  EXPECT_DOUBLE_EQ(p[0].position.z, 11.5);     // raised to 1.5 m over the ground
  EXPECT_DOUBLE_EQ(p[0].near_m, 0.125 * 1.5);  // within reach of the ground below
  EXPECT_DOUBLE_EQ(p[1].position.z, 40.0);     // high enough: kept
  EXPECT_DOUBLE_EQ(p[1].near_m, 2.0);          // 0.125 x 30 m is further: kept
}

}  // namespace
}  // namespace terrasprite
