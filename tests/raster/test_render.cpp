// SPDX-License-Identifier: MIT
// GL rendering on the headless device (llvmpipe in CI): known scenes land on
// known pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "terrasprite/gl_context.h"
#include "terrasprite/mesh_renderer.h"
#include "terrasprite/terrain.h"
#include "terrasprite/terrain_gen.h"

using namespace terrasprite;

namespace {

GlContext& gl() {
  static GlContext context;  // one per test process; GL objects die before exit via scopes
  return context;
}

// A flat 64 m x 64 m plane (65 x 65 samples, 1 m) with an 8 x 8 checkerboard.
Terrain checker_plane() {
  Terrain t;
  Heightfield& h = t.heights;
  h.width = h.height = 65;
  h.heights.assign(65 * 65, 0.f);
  t.texture = checker_texture(8, 256);
  t.texture_name = "checker";
  return t;
}

// Straight down from the height at which the plane exactly fills a 60-degree view.
Camera overhead(double z) {
  Camera c = Camera::look_at({0, 0, z}, {0, 0, 0}, 60, 1.0, 0.0);
  c.near_m = 1;
  c.far_m = 1000;
  return c;
}

bool is_red(const std::uint8_t* p) {
  return p[0] > 150 && p[1] < 100;
}
bool is_green(const std::uint8_t* p) {
  return p[1] > 120 && p[0] < 100;
}

}  // namespace

TEST(Render, CheckerboardSeenStraightDownLandsOnExpectedPixels) {
  gl();
  Terrain t = checker_plane();
  GlTerrain scene(t);
  MeshRenderer full(scene, 256, 256, 0);
  const double z = 32.0 / std::tan(glm::radians(30.0));
  Frame f = full.render(overhead(z));
  ASSERT_EQ(f.width(), 256);
  // Each square spans 32 pixels; square (0, 0) at the north-west corner is red.
  for (int sy = 0; sy < 8; ++sy)
    for (int sx = 0; sx < 8; ++sx) {
      const std::uint8_t* p = f.color.px(sx * 32 + 16, sy * 32 + 16);
      if ((sx + sy) % 2 == 0)
        EXPECT_TRUE(is_red(p)) << sx << "," << sy;
      else
        EXPECT_TRUE(is_green(p)) << sx << "," << sy;
    }
  // Depth along the view axis is the camera height everywhere on a flat plane.
  ASSERT_EQ(f.depth.size(), 256u * 256u);
  EXPECT_NEAR(f.depth[128 * 256 + 128], z, 1e-3 * z);
  EXPECT_NEAR(f.depth[5 * 256 + 250], z, 1e-3 * z);
  EXPECT_EQ(f.triangles, 2LL * 64 * 64);
  EXPECT_EQ(f.cls, "full");
}

TEST(Render, SkyWhereNothingIsDrawn) {
  gl();
  Terrain t = checker_plane();
  GlTerrain scene(t);
  MeshRenderer full(scene, 64, 64, 0);
  Frame f = full.render(overhead(200));  // plane covers the middle only
  EXPECT_TRUE(std::isinf(f.depth[0]));
  const std::uint8_t* corner = f.color.px(0, 0);
  EXPECT_EQ(corner[0], kSkyColor[0]);
  EXPECT_EQ(corner[1], kSkyColor[1]);
  EXPECT_EQ(corner[2], kSkyColor[2]);
  EXPECT_TRUE(std::isfinite(f.depth[32 * 64 + 32]));
}

TEST(Render, FullAndSixteenQuadsAgreeOnAFlatPlane) {
  gl();
  // A smooth texture: on a hard checker edge, rounding differences between a
  // large and a small triangle's interpolation (~1e-4 of a texel span) swing a
  // bilinear sample by several units, which says nothing about the meshes.
  Terrain t = checker_plane();
  t.texture = Image(256, 256);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      std::uint8_t* p = t.texture.px(x, y);
      p[0] = std::uint8_t(128 + 100 * std::sin(x * 0.05));
      p[1] = std::uint8_t(128 + 100 * std::cos(y * 0.07));
      p[2] = std::uint8_t((x + y) / 2);
      p[3] = 255;
    }
  GlTerrain scene(t);
  MeshRenderer full(scene, 128, 128, 0), lod(scene, 128, 128, 16);
  Camera oblique = Camera::look_at({10, -60, 30}, {0, 0, 0}, 60, 1.0);
  oblique.near_m = 1;
  oblique.far_m = 500;
  for (const Camera& c : {overhead(60.0), oblique}) {
    Frame a = full.render(c), b = lod.render(c);
    int worst = 0;
    long long off = 0;
    for (std::size_t i = 0; i < a.color.rgba.size(); ++i) {
      int d = std::abs(int(a.color.rgba[i]) - int(b.color.rgba[i]));
      worst = std::max(worst, d);
      off += d > 1;
    }
    // Interpolated texture coordinates differ only by rounding across triangles.
    EXPECT_LE(off, 0) << "worst channel difference " << worst;
    EXPECT_EQ(b.triangles, 2 * 16 * 16);
  }
}

TEST(Render, SyntheticTerrainCoversTheViewWithoutSky) {
  gl();
  TerrainOptions o;
  o.synthetic_size = 257;  // 7680 m across
  Terrain t = load_terrain(o);
  GlTerrain scene(t);
  MeshRenderer full(scene, 96, 96, 0);
  // Above the centre, looking 75 degrees down: even the corner rays (39 degrees
  // down) meet the ground within 2.6 km, inside the terrain's 3.84 km half-extent.
  Camera c;
  c.position = {0, 0, t.heights.max_height() + 100.0};
  c.pitch_deg = -75;
  fit_clip_planes(c, t.heights);
  Frame f = full.render(c);
  int sky = 0;
  for (float d : f.depth) sky += std::isinf(d);
  EXPECT_EQ(sky, 0);
  EXPECT_GT(f.ms, 0.0);
}

TEST(Render, ContextNamesItsRenderer) {
  EXPECT_FALSE(gl().renderer().empty());
}
