// SPDX-License-Identifier: MIT
// GL rendering on the headless device (llvmpipe in CI): known scenes land on
// known pixels.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <thread>
#include <vector>

#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/terrain/texture_gen.h"

using namespace terrasprite;

namespace {

GlContext& gl_ctx() {
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
  gl_ctx();
  Terrain t = checker_plane();
  Scene scene(t);
  MeshRenderer full(scene, 256, 256, 0);
  const double z = 32.0 / std::tan(glm::radians(30.0));
  Frame f = full.render(overhead(z), ReadBack::kColorDepth);
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
  EXPECT_EQ(f.cls, FrameClass::kFull);
}

TEST(Render, SkyWhereNothingIsDrawn) {
  gl_ctx();
  Terrain t = checker_plane();
  Scene scene(t);
  MeshRenderer full(scene, 64, 64, 0);
  Frame f = full.render(overhead(200), ReadBack::kColorDepth);  // plane covers the middle only
  EXPECT_TRUE(std::isinf(f.depth[0]));
  const std::uint8_t* corner = f.color.px(0, 0);
  EXPECT_EQ(corner[0], kSkyColor[0]);
  EXPECT_EQ(corner[1], kSkyColor[1]);
  EXPECT_EQ(corner[2], kSkyColor[2]);
  EXPECT_TRUE(std::isfinite(f.depth[32 * 64 + 32]));
}

TEST(Render, FullAndSixteenQuadsAgreeOnAFlatPlane) {
  gl_ctx();
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
  Scene scene(t);
  // The same drape filter on both: this compares meshes, not filters.
  MeshRenderer full(scene, 128, 128, 0),
      lod(scene, 128, 128, 16, RasterOptions{.drape_filter = DrapeFilter::kHardware});
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
  gl_ctx();
  TerrainOptions o;
  o.synthetic_size = 257;  // 7680 m across
  Terrain t = load_terrain(o);
  Scene scene(t);
  MeshRenderer full(scene, 96, 96, 0);
  // Above the centre, looking 75 degrees down: even the corner rays (39 degrees
  // down) meet the ground within 2.6 km, inside the terrain's 3.84 km half-extent.
  Camera c;
  c.position = {0, 0, t.heights.max_height() + 100.0};
  c.pitch_deg = -75;
  fit_clip_planes(c, t.heights);
  Frame f = full.render(c, ReadBack::kDepth);
  ASSERT_EQ(f.depth.size(), 96u * 96u);
  EXPECT_TRUE(f.color.rgba.empty());  // only what was asked for is read back
  int sky = 0;
  for (float d : f.depth) sky += std::isinf(d);
  EXPECT_EQ(sky, 0);
}

TEST(Render, ContextNamesItsRenderer) {
  // "unknown" is what renderer() says when GL_RENDERER gives nothing.
  EXPECT_NE(gl_ctx().renderer(), "unknown");
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 45);
}

namespace terrasprite {
namespace {

// A caller's framebuffer (as a window's would be): colour + float depth.
struct CallerTarget {
  GLuint color = 0, depth = 0, fbo = 0;
  CallerTarget(int w, int h) {
    glCreateTextures(GL_TEXTURE_2D, 1, &color);
    glTextureStorage2D(color, 1, GL_RGBA8, w, h);
    glCreateTextures(GL_TEXTURE_2D, 1, &depth);
    glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, w, h);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
  }
  ~CallerTarget() {
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &color);
    glDeleteTextures(1, &depth);
  }
};

TEST(Render, DrawsIntoACallersTargetDespiteForeignGlState) {
  gl_ctx();
  TerrainOptions o;
  o.synthetic_size = 65;
  Terrain t = load_terrain(o);
  Scene scene(t);
  MeshRenderer own(scene, 80, 60, 0), other(scene, 80, 60, 0);
  Camera c = Camera::look_at({-3000, -3000, 2500}, {0, 0, 500}, 60, 80.0 / 60.0);
  fit_clip_planes(c, t.heights);
  const Frame a = own.render(c, ReadBack::kColorDepth);
  CallerTarget target(80, 60);
  other.set_output(GlTarget{target.fbo, 80, 60});
  // What a UI pass leaves behind: blending, scissor, culling, a half viewport.
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 10, 10);
  glEnable(GL_CULL_FACE);
  glViewport(0, 0, 40, 30);
  const Frame b = other.render(c, ReadBack::kColorDepth);
  EXPECT_EQ(b.width(), 80);
  EXPECT_EQ(a.color.rgba, b.color.rgba);
  ASSERT_EQ(a.depth.size(), b.depth.size());
  for (std::size_t i = 0; i < a.depth.size(); i += 97) EXPECT_EQ(a.depth[i], b.depth[i]);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
}

TEST(Render, SharedContextSeesTexturesOnAnotherThread) {
  GlContext& first = gl_ctx();
  const std::vector<std::uint8_t> texels = {1, 2, 3, 4, 250, 251, 252, 253};
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  glTextureStorage2D(tex, 1, GL_RGBA8, 2, 1);
  glTextureSubImage2D(tex, 0, 0, 0, 2, 1, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  glFinish();
  std::unique_ptr<GlContext> second = first.create_shared();
  std::vector<std::uint8_t> seen(8, 0);
  std::thread worker([&] {
    second->make_current();
    glGetTextureImage(tex, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(seen.size()), seen.data());
    second->release_current();
  });
  worker.join();
  EXPECT_EQ(seen, texels);
  second.reset();
  first.make_current();
  glDeleteTextures(1, &tex);
}

}  // namespace
}  // namespace terrasprite
