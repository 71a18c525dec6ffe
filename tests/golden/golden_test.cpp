// SPDX-License-Identifier: MIT
// Golden images: each renderer (full, LOD, LOD-sprite, voxel) on fixed views
// of a small synthetic terrain, compared with stored 128 x 96 images under a
// tolerance. TS_GOLDEN_UPDATE=1 rewrites the stored images and prints what
// changed (PSNR/SSIM of the new image against the old one).
//
// Tolerance: SSIM >= 0.98 and PSNR >= 32 dB. llvmpipe renders bit-identically
// run to run on one machine; the margin absorbs another driver's rasterisation
// rules and texture filtering (a GPU), and the AVX2 vs baseline clones of
// the voxel renderer, while a real change (a shifted view, a lost texture, a
// broken fallback) drops SSIM far below it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include "terrasprite/gl/gl_context.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite {
namespace {

constexpr int kW = 128, kH = 96;
constexpr double kMinSsim = 0.98, kMinPsnr = 32.0;

const Terrain& terrain() {
  static const Terrain t = [] {
    TerrainOptions o;
    o.synthetic_size = 129;
    return load_terrain(o);
  }();
  return t;
}

// Two views: an oblique one over the terrain and a steep one near the ground.
Camera view(int k) {
  const Heightfield& h = terrain().heights;
  const double E = h.extent();
  Camera c = k == 0 ? Camera::look_at({-0.7 * E, -0.6 * E, h.max_height() + 0.3 * E},
                                      {0, 0, h.min_height()}, 60, double(kW) / kH)
                    : Camera::look_at({0.2 * E, -0.25 * E, h.max_height() + 0.05 * E},
                                      {0.05 * E, 0.1 * E, h.min_height()}, 50, double(kW) / kH);
  fit_clip_planes(c, h);
  return c;
}

std::filesystem::path golden_path(const std::string& name) {
  return std::filesystem::path(TS_SOURCE_DIR) / "tests" / "golden_images" / (name + ".png");
}

void check_golden(const std::string& name, const Image& image) {
  const std::filesystem::path file = golden_path(name);
  const char* update = std::getenv("TS_GOLDEN_UPDATE");
  if (update && std::string(update) == "1") {
    if (std::filesystem::exists(file)) {
      const Image old = load_image(file.string());
      if (old.width == image.width && old.height == image.height) {
        std::printf("golden %s: rewritten; new vs old PSNR %.2f dB, SSIM %.4f\n", name.c_str(),
                    quality::psnr(old.view(), image.view()).rgb,
                    quality::ssim(old.view(), image.view()).ssim);
      } else {
        std::printf("golden %s: rewritten (size changed)\n", name.c_str());
      }
    } else {
      std::printf("golden %s: new\n", name.c_str());
    }
    save_png(image, file.string());
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(file))
      << file << " is missing: run with TS_GOLDEN_UPDATE=1 to create it";
  const Image golden = load_image(file.string());
  ASSERT_EQ(golden.width, image.width);
  ASSERT_EQ(golden.height, image.height);
  const double psnr = quality::psnr(golden.view(), image.view()).rgb;
  const double ssim = quality::ssim(golden.view(), image.view()).ssim;
  EXPECT_GE(ssim, kMinSsim) << name << ": PSNR " << psnr << " dB";
  EXPECT_GE(psnr, kMinPsnr) << name << ": SSIM " << ssim;
}

GlContext& gl_ctx() {
  static GlContext context;
  return context;
}

TEST(Golden, FullResolution) {
  gl_ctx();
  Scene scene(terrain());
  MeshRenderer r(scene, kW, kH, 0);
  for (int k : {0, 1}) check_golden("full_" + std::to_string(k), r.render(view(k)).color);
}

TEST(Golden, Lod) {
  gl_ctx();
  Scene scene(terrain());
  MeshRenderer r(scene, kW, kH, 16);
  for (int k : {0, 1}) check_golden("lod_" + std::to_string(k), r.render(view(k)).color);
}

TEST(Golden, Sprite) {
  gl_ctx();
  Scene scene(terrain());
  SpriteRenderer r(scene, kW, kH);
  // Keyframe at a view, then a sprite frame a little to the side of it.
  for (int k : {0, 1}) {
    Camera key = view(k), moved = key;
    moved.position += 0.02 * terrain().heights.extent() * moved.right();
    fit_clip_planes(moved, terrain().heights);
    r.render_keyframe(key);
    Frame f = r.render_sprite(moved);
    ASSERT_EQ(f.cls, FrameClass::kSprite);
    check_golden("sprite_" + std::to_string(k), f.color);
  }
}

TEST(Golden, Voxel) {
  VoxelTerrain vt(terrain());
  VoxelRenderer r(vt, kW, kH);
  for (int k : {0, 1}) check_golden("voxel_" + std::to_string(k), r.render(view(k)).color);
}

}  // namespace
}  // namespace terrasprite
