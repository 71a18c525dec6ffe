// SPDX-License-Identifier: MIT
// The LOD-sprite renderer on GL: a sprite from the keyframe's own camera,
// the visibility fallback (occlusion and the keyframe frustum), the trigger.
#include "terrasprite/sprite/sprite_renderer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sprite_test_util.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/terrain/synth.h"
#include "terrasprite/terrain/texture_gen.h"

namespace terrasprite {
namespace {

using namespace sprite_test;

Terrain gentle_hills(int n) {
  Terrain t;
  Heightfield& h = t.heights;
  h.width = h.height = n;
  h.spacing_x = h.spacing_y = 10.0;
  h.name = "hills";
  h.heights.resize(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) h.at(i, j) = float(30.0 * std::sin(i * 0.07) * std::cos(j * 0.05));
  t.texture = derived_texture(h, 2 * (n - 1), 2 * (n - 1));
  return t;
}

Camera tilted_view(const Heightfield& h, double pitch_deg, glm::dvec3 offset = glm::dvec3(0)) {
  const double E = h.extent();
  Camera c = Camera::look_at(glm::dvec3(0, -E * std::cos(glm::radians(-pitch_deg)),
                                        E * std::sin(glm::radians(-pitch_deg))) +
                                 offset,
                             offset, 60.0, 1.0);
  fit_clip_planes(c, h);
  return c;
}

bool is_sky(const std::uint8_t* p) {
  return p[0] == kSkyColor[0] && p[1] == kSkyColor[1] && p[2] == kSkyColor[2];
}

TEST(SpriteRenderer, SpriteFromTheKeyframeCameraMatchesTheKeyframe) {
  GlContext gl;
  Terrain t = gentle_hills(129);
  Scene scene(t);
  SpriteRenderer r(scene, 256, 256,
                   SpriteOptions{.lod_quads = 16, .sharp_px = 0});  // every quad from the keyframe
  for (double pitch : {-90.0, -60.0, -35.0}) {
    Camera c = tilted_view(t.heights, pitch);
    Frame key = r.render_keyframe(c);
    Frame sprite = r.render_sprite(c);
    EXPECT_EQ(key.cls, FrameClass::kKey);
    EXPECT_EQ(sprite.cls, FrameClass::kSprite);
    EXPECT_GT(psnr(key.color, sprite.color), 40.0) << pitch;
    EXPECT_LT(sprite.triangles, key.triangles);
  }
}

// Keyframes framed wider than the view (a margin) and denser (supersampled):
// a keyframe's own frame is its middle, the same image as an unframed
// keyframe's; a sprite drawn from it matches; and a quad just outside the
// view, which an unframed keyframe cannot texture, is in the framed one.
// CI cost: about 0.5 s.
TEST(SpriteRenderer, KeyframesFramedWiderAndDenserShowTheSameView) {
  GlContext gl;
  Terrain t = gentle_hills(129);
  Scene scene(t);
  const SpriteOptions plain{.lod_quads = 16, .sharp_px = 0};
  SpriteOptions margin = plain, dense = plain;
  margin.key_margin = 0.125;  // 16 pixels of 128 on each side: an exact crop
  dense.key_margin = 0.125;
  dense.key_supersample = 1.5;
  SpriteRenderer r0(scene, 128, 128, plain), rm(scene, 128, 128, margin),
      rs(scene, 128, 128, dense);
  const Camera c = tilted_view(t.heights, -50.0);
  const Frame k0 = r0.render_keyframe(c), km = rm.render_keyframe(c), ks = rs.render_keyframe(c);
  EXPECT_EQ(km.cls, FrameClass::kKey);
  EXPECT_GT(psnr(k0.color, km.color), 45.0);  // the same pixels, up to the projection's rounding
  EXPECT_GT(psnr(k0.color, ks.color), 28.0);  // resampled from 1.5x as many pixels
  EXPECT_EQ(rm.keyframe_camera().position, c.position);
  EXPECT_GT(rm.keyframe_camera().fov_y_deg, c.fov_y_deg + 5);
  EXPECT_GT(psnr(k0.color, rm.render_sprite(c).color), 40.0);
  // Framed as the view, the keyframe's own error and scale are nil.
  EXPECT_NEAR(rm.error(c).resample_scale, 1.0, 1e-6);
  EXPECT_NEAR(rs.error(c).resample_scale, 1.0, 1e-6);
  EXPECT_NEAR(rs.error(c).paper_px, 0.0, 1e-9);
  // Turned so that part of the view lies outside the unframed keyframe:
  // fewer of its quads fall back with the margin.
  Camera turned = c;
  turned.yaw_deg += 8.0;
  EXPECT_GT(r0.error(turned).fallback_fraction(), 0.0);
  EXPECT_LT(rm.error(turned).fallback_fraction(), r0.error(turned).fallback_fraction());
}

// A wall-like ridge across the terrain hides the valley north of it from a
// low keyframe camera in the south. Seen from above, the valley must show the
// drape texture (green), not keyframe pixels smeared from the ridge (red).
TEST(SpriteRenderer, ValleyHiddenByARidgeTakesTheOriginalTexture) {
  GlContext gl;
  Terrain t;
  Heightfield& h = t.heights;
  h.width = h.height = 65;
  h.spacing_x = h.spacing_y = 10.0;
  h.name = "ridge";
  h.heights.assign(65 * 65, 0.f);
  for (int j = 28; j <= 36; ++j)
    for (int i = 0; i < 65; ++i) h.at(i, j) = 150.f;
  t.texture = Image(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = t.texture.px(x, y);
      const bool ridge = y >= 26 && y <= 38;
      p[0] = ridge ? 230 : 20;
      p[1] = ridge ? 20 : 200;
      p[2] = 20;
      p[3] = 255;
    }
  Scene scene(t);
  SpriteRenderer r(scene, 256, 256, SpriteOptions{.lod_quads = 8});
  Camera key = Camera::look_at({0, -700, 40}, {0, 0, 100}, 60.0, 1.0);
  fit_clip_planes(key, h);
  r.render_keyframe(key);
  // Valley quads (coarse rows 0-2, north of the ridge) are hidden: fallback.
  const auto& fb = r.fallback_quads();
  for (int row = 0; row <= 2; ++row)
    for (int col = 2; col < 6; ++col) EXPECT_EQ(fb[row * 8 + col], 1) << row << "," << col;
  // South plain quads near the view centre are visible: keyframe texture.
  EXPECT_EQ(fb[6 * 8 + 3], 0);

  Camera above = Camera::look_at({0, -100, 900}, {0, 150, 0}, 60.0, 1.0);
  fit_clip_planes(above, h);
  Frame f = r.render_sprite(above);
  int checked = 0;
  for (double y = 180; y <= 300; y += 20)
    for (double x = -150; x <= 150; x += 50) {
      glm::dvec2 px;
      ASSERT_TRUE(project_to_pixel(above, 256, 256, {x, y, 0}, px));
      if (px.x < 1 || px.y < 1 || px.x > 255 || px.y > 255) continue;
      const std::uint8_t* p = f.color.px(int(px.x), int(px.y));
      EXPECT_GT(p[1], 150) << "valley point " << x << "," << y << " not green";
      EXPECT_LT(p[0], 80) << "valley point " << x << "," << y << " shows smeared ridge pixels";
      ++checked;
    }
  EXPECT_GT(checked, 10);
}

// The keyframe sees only the west of the terrain; a view of the east, all
// terrain, is textured everywhere (never sky or black), like plain LOD.
TEST(SpriteRenderer, GeometryFromOutsideTheKeyframeIsTextured) {
  GlContext gl;
  Terrain t = gentle_hills(129);
  Scene scene(t);
  SpriteRenderer r(scene, 128, 128, SpriteOptions{.lod_quads = 16});
  MeshRenderer lod(scene, 128, 128, 16);
  Camera west = Camera::look_at({-400, 0, 500}, {-400, 0, 0}, 60.0, 1.0);
  Camera east = Camera::look_at({350, 0, 400}, {350, 0, 0}, 60.0, 1.0);
  fit_clip_planes(west, t.heights);
  fit_clip_planes(east, t.heights);
  r.render_keyframe(west);
  Frame f = r.render_sprite(east);
  int blank = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const std::uint8_t* p = f.color.px(x, y);
      if (is_sky(p) || (p[0] + p[1] + p[2]) == 0) ++blank;
    }
  EXPECT_EQ(blank, 0);
  EXPECT_GT(psnr(lod.render(east).color, f.color), 35.0);
}

// The scale trigger's limit: the constant where plain LOD is nearly right,
// 1 + k x its drape error where that is higher.
TEST(ScaleTrigger, GivesWayWherePlainLodIsFarOff) {
  SpriteOptions o;  // 1.25, k = 1/16
  SpriteError e;
  EXPECT_DOUBLE_EQ(scale_trigger_limit(o, e), 1.25);
  e.drape_px = 4.0;  // 1 + 4/16 = 1.25
  EXPECT_DOUBLE_EQ(scale_trigger_limit(o, e), 1.25);
  e.drape_px = 8.0;
  EXPECT_DOUBLE_EQ(scale_trigger_limit(o, e), 1.5);
  o.scale_per_drape_px = 0;
  EXPECT_DOUBLE_EQ(scale_trigger_limit(o, e), 1.25);
  o.max_resample_scale = INFINITY;
  o.scale_per_drape_px = 1.0 / 16;
  EXPECT_EQ(scale_trigger_limit(o, e), INFINITY);
}

// The renderer's decision reads that limit. CI cost: ~0.1 s.
TEST(SpriteRenderer, ScaleTriggerReadsTheDrapeError) {
  GlContext gl;
  Terrain t = gentle_hills(33);
  Scene scene(t);
  SpriteRenderer r(scene, 64, 64, {.lod_quads = 4});
  SpriteError e;
  e.resample_scale = 1.4;
  e.drape_px = 1.0;
  EXPECT_EQ(r.trigger_for(e), Trigger::kScale);
  e.drape_px = 8.0;  // limit 1.5
  EXPECT_EQ(r.trigger_for(e), std::nullopt);
  SpriteRenderer constant(scene, 64, 64, {.lod_quads = 4, .scale_per_drape_px = 0});
  EXPECT_EQ(constant.trigger_for(e), Trigger::kScale);
  EXPECT_THROW(SpriteRenderer(scene, 64, 64, {.lod_quads = 4, .scale_per_drape_px = -1}),
               InputError);
}

TEST(SpriteRenderer, KeyframeTriggerFiresWhenTheThresholdIsExceededAndNotBefore) {
  GlContext gl;
  SynthOptions so;
  so.size = 129;
  Terrain t;
  t.heights = synthesize_terrain(so);
  t.texture = derived_texture(t.heights, 256, 256);
  Scene scene(t);
  for (ErrorMetric m : {ErrorMetric::kPaper, ErrorMetric::kExact}) {
    SpriteOptions o{
        .lod_quads = 16, .threshold_px = 0.5, .metric = m, .max_resample_scale = INFINITY};
    SpriteRenderer r(scene, 128, 128, o);
    auto path = paper_path(t.heights, 120, 1.0);
    int keys = 0;
    for (std::size_t i = 0; i < path.size(); ++i) {
      const SpriteError before = r.error(path[i]);
      Frame f = r.draw(path[i]);
      const bool expect_key = i == 0 || before.value(m) > o.threshold_px;
      EXPECT_EQ(f.cls, expect_key ? FrameClass::kKey : FrameClass::kSprite)
          << i << " error " << before.value(m);
      if (i > 0) {
        EXPECT_DOUBLE_EQ(r.last_error().value(m), before.value(m));
      }
      if (f.cls == FrameClass::kSprite) {
        EXPECT_LE(r.last_error().value(m), o.threshold_px);
      }
      keys += f.cls == FrameClass::kKey;
    }
    EXPECT_GT(keys, 1);
    EXPECT_LT(keys, 120);
  }
}

}  // namespace
}  // namespace terrasprite
