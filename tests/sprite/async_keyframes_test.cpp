// SPDX-License-Identifier: MIT
// Asynchronous LOD-sprite keyframes: the worker's textures are complete and
// equal to a keyframe drawn in the caller's context, sprite frames stay close
// to the synchronous renderer's (never sky-only or black where those are not),
// and the worker shuts down cleanly whatever it is doing. No timing is asserted.
#include "sprite/async_keyframes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sprite_test_util.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {
namespace {

using namespace sprite_test;

std::vector<std::uint8_t> texture_bytes(GLuint texture, int w, int h) {
  std::vector<std::uint8_t> out(std::size_t(w) * h * 4);
  glGetTextureImage(texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(out.size()), out.data());
  return out;
}

struct Coverage {
  double terrain = 0, black = 0;  // fractions of the pixels
};
Coverage coverage(const Image& im) {
  Coverage c;
  const std::size_t n = im.rgba.size() / 4;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = &im.rgba[4 * i];
    const bool sky = p[0] == kSkyColor[0] && p[1] == kSkyColor[1] && p[2] == kSkyColor[2];
    c.terrain += !sky;
    c.black += p[0] == 0 && p[1] == 0 && p[2] == 0;
  }
  c.terrain /= double(n);
  c.black /= double(n);
  return c;
}

// The worker's keyframe, read in the caller's context after take(), has the
// very pixels and visibility of one drawn here; a slot given back is reused.
TEST(AsyncKeyframes, LandedTexturesEqualAKeyframeDrawnHere) {
  GlContext gl;
  Terrain t = small_mountains();
  Scene scene(t);
  const int w = 64, h = 64;
  const auto grid = std::make_shared<const CoarseGrid>(make_coarse_grid(t.heights, 16));
  const std::vector<Camera> path = paper_path(t.heights, 20, 1.0);
  AsyncKeyframes worker(
      gl, t, [&](const Camera&) { return grid; }, w, h, /*lighting=*/false, /*contrast=*/false,
      TerrainShading::kPlain);
  Keyframe here(w, h);
  for (int i : {0, 10, 19}) {
    worker.request(path[i]);
    const Keyframe* k = worker.wait();
    ASSERT_NE(k, nullptr);
    EXPECT_FALSE(worker.busy());
    here.capture(scene.terrain_gpu(), grid, path[i], false);
    const auto theirs = texture_bytes(k->target.color_texture(), w, h);
    EXPECT_EQ(theirs, texture_bytes(here.target.color_texture(), w, h)) << i;
    std::size_t opaque = 0;
    for (std::size_t p = 3; p < theirs.size(); p += 4) opaque += theirs[p] != 0;
    EXPECT_GT(opaque, theirs.size() / 4 / 8) << i;  // terrain, not an empty texture
    EXPECT_EQ(k->fallback, here.fallback) << i;
    EXPECT_TRUE(k->valid);
    worker.give_back(k);
  }
  EXPECT_EQ(worker.take(), nullptr);  // nothing in flight
  EXPECT_EQ(worker.finished(), 3);
}

struct Flight {
  std::vector<Image> frames;
  AsyncKeyframeStats stats;
};

Flight fly(Scene& scene, const std::vector<Camera>& path, SpriteOptions o, bool wait) {
  SpriteRenderer r(scene, 64, 64, o);
  Flight run;
  for (const Camera& c : path) {
    run.frames.push_back(r.render(c).color);
    if (wait) r.wait_for_keyframe();
  }
  run.stats = r.async_stats();
  return run;
}

// Waiting for each keyframe makes the async run independent of the worker's
// speed (each lands on the frame after its request): it then stays within
// 2 dB of the synchronous run against full resolution. Free-running, which
// keyframe is current depends on timing (its 40 frames let a few land), but
// no frame may lose terrain or turn black where full resolution shows terrain.
TEST(AsyncSprite, FramesStayCloseToTheSynchronousRenderer) {
  GlContext gl;
  Terrain t = small_mountains();
  Scene scene(t);
  // Consecutive frames of the paper path: a few keyframes, mostly sprites.
  const std::vector<Camera> whole = paper_path(t.heights, 230, 1.0);
  const std::vector<Camera> path(whole.begin() + 60, whole.begin() + 100);
  const std::vector<Camera> first(path.begin(), path.begin() + 20);
  MeshRenderer full(scene, 64, 64, 0);
  std::vector<Image> refs;
  for (const Camera& c : path) refs.push_back(full.render(c).color);
  const Flight sync_run = fly(scene, first, {}, false);
  const Flight waited = fly(scene, first, {.async_context = &gl}, true);
  const Flight free = fly(scene, path, {.async_context = &gl}, false);
  EXPECT_EQ(sync_run.stats.requested, 0);
  EXPECT_GE(waited.stats.used, 1);
  EXPECT_EQ(waited.stats.landed, waited.stats.requested);
  EXPECT_DOUBLE_EQ(waited.stats.last_latency_frames, 1.0);
  // PSNR of the summed error: a keyframe (error 0) does not dominate the mean.
  double se_sync = 0, se_waited = 0;
  for (std::size_t i = 0; i < first.size(); ++i) {
    se_sync += std::pow(10.0, -psnr(refs[i], sync_run.frames[i]) / 10);
    se_waited += std::pow(10.0, -psnr(refs[i], waited.frames[i]) / 10);
  }
  EXPECT_GT(-10 * std::log10(se_waited), -10 * std::log10(se_sync) - 2.0);
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Coverage want = coverage(refs[i]);
    for (const Flight* a : {&sync_run, &waited, &free}) {
      if (i >= a->frames.size()) continue;
      const Coverage c = coverage(a->frames[i]);
      EXPECT_GT(c.terrain, 0.9 * want.terrain) << i;
      EXPECT_LE(c.black, want.black + 0.01) << i;
      EXPECT_GT(psnr(refs[i], a->frames[i]), 15.0) << i;
    }
  }
}

// Destroyed with a keyframe being rendered, with one landed and never taken,
// and after a reset() dropped one in flight: no hang, nothing leaked (ASan).
TEST(AsyncSprite, ShutsDownCleanlyMidKeyframe) {
  GlContext gl;
  Terrain t = small_mountains();
  Scene scene(t);
  const std::vector<Camera> path = paper_path(t.heights, 4, 1.0);
  const SpriteOptions o{.async_context = &gl};
  {  // mid-render: the far camera triggers a request, then the renderer goes
    SpriteRenderer r(scene, 128, 128, o);
    r.draw(path[0]);
    r.draw(path[3]);
    EXPECT_EQ(r.async_stats().requested, 1);
  }
  {  // landed, never taken
    SpriteRenderer r(scene, 128, 128, o);
    r.draw(path[0]);
    r.draw(path[3]);
    r.wait_for_keyframe();
  }
  {  // dropped by reset(), then a fresh start
    SpriteRenderer r(scene, 128, 128, o);
    r.draw(path[0]);
    r.draw(path[3]);
    r.reset();
    EXPECT_EQ(r.draw(path[1]).cls, FrameClass::kKey);
    r.draw(path[3]);
    r.wait_for_keyframe();
    r.draw(path[3]);
    EXPECT_EQ(r.async_stats().requested, 1);
  }
  EXPECT_THROW(SpriteRenderer(scene, 64, 64, {.cache_bytes = 1 << 20, .async_context = &gl}),
               InputError);
}

// async_first_keyframe: no frame waits for the first keyframe; the coarse
// mesh with the drape ("lod") is drawn until it lands, then sprites follow.
TEST(AsyncSprite, FirstKeyframeFromTheWorkerDrawsPlainLodMeanwhile) {
  GlContext gl;
  Terrain t = small_mountains();
  Scene scene(t);
  const std::vector<Camera> path = paper_path(t.heights, 8, 1.0);
  SpriteRenderer r(scene, 96, 96, {.async_context = &gl, .async_first_keyframe = true});
  const Frame first = r.render(path[0]);
  EXPECT_EQ(first.cls, FrameClass::kLod);
  EXPECT_FALSE(r.has_keyframe());
  EXPECT_EQ(r.async_stats().requested, 1);
  MeshRenderer full(scene, 96, 96, 0);
  const Coverage want = coverage(full.render(path[0]).color);
  EXPECT_GT(coverage(first.color).terrain, 0.9 * want.terrain);  // drawn, not left empty
  EXPECT_LE(coverage(first.color).black, want.black + 0.01);
  r.wait_for_keyframe();
  const Frame next = r.render(path[1]);
  EXPECT_EQ(next.cls, FrameClass::kSprite);
  EXPECT_TRUE(r.has_keyframe());
  EXPECT_TRUE(r.last_landed());
  EXPECT_EQ(r.async_stats().used, 1);
}

}  // namespace
}  // namespace terrasprite
