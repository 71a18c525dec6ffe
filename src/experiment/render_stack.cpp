// SPDX-License-Identifier: MIT
#include "terrasprite/experiment/render_stack.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "terrasprite/common/error.h"
#include "terrasprite/raster/mesh_renderer.h"

namespace terrasprite {
namespace {

// 1 <= quads <= the terrain's quads along its shorter side: a coarser grid
// is not a LOD, a finer one would be clamped silently.
void check_lod_quads(int quads, const Heightfield& h) {
  const int most = std::min(h.width, h.height) - 1;
  if (quads < 1 || quads > most)
    throw InputError(
        fmt::format("lod_quads {}: must be between 1 and {} for the {}x{}-sample terrain", quads,
                    most, h.width, h.height));
}

// GL modes: the caller's current context, else one of our own.
void use_gl(RenderStack& s, const RenderStackOptions& o) {
  if (!o.context) s.gl = std::make_unique<GlContext>();
  s.device = (o.context ? o.context : s.gl.get())->renderer();
}

void add_mesh_renderer(RenderStack& s, const Terrain& terrain, const RenderStackOptions& o,
                       int width, int height) {
  const bool lod = o.mode == RenderMode::kLod;
  if (lod) check_lod_quads(o.lod_quads, terrain.heights);
  use_gl(s, o);
  s.scene = std::make_unique<Scene>(terrain);
  s.real = std::make_unique<MeshRenderer>(*s.scene, width, height, lod ? o.lod_quads : 0,
                                          RasterOptions{o.lighting});
}

void add_sprite_renderer(RenderStack& s, const Terrain& terrain, const RenderStackOptions& o,
                         int width, int height) {
  check_lod_quads(o.lod_quads, terrain.heights);
  SpriteOptions so;
  so.lod_quads = o.lod_quads;
  so.threshold_px = o.sprite_threshold_px;
  so.lighting = o.lighting;
  so.mesh = o.sprite_mesh;
  so.mesh_triangles = o.sprite_mesh_triangles;
  use_gl(s, o);
  if (o.async_keyframes) {
    so.async_context = o.context ? o.context : s.gl.get();
    so.async_first_keyframe = true;  // a mode or threshold switch never waits for a keyframe
  }
  s.scene = std::make_unique<Scene>(terrain);
  s.real = std::make_unique<SpriteRenderer>(*s.scene, width, height, so);
}

void add_voxel_renderer(RenderStack& s, const Terrain& terrain, const RenderStackOptions& o,
                        int width, int height) {
  const VoxelTerrain* voxels = o.voxels;
  if (!voxels) {
    s.voxel = std::make_unique<VoxelTerrain>(terrain);
    voxels = s.voxel.get();
  }
  VoxelOptions vo;
  vo.pixel_voxel_ratio = o.voxel_ratio;
  auto r = std::make_unique<VoxelRenderer>(*voxels, width, height, vo);
  s.device = fmt::format("cpu voxel {}, {} threads", to_string(r->options().variant),
                         std::max(1u, std::thread::hardware_concurrency()));
  s.real = std::move(r);
}

}  // namespace

int auto_lod_quads(const Heightfield& h) {
  const int quads = std::min(h.width, h.height) - 1;
  constexpr double kSamplesPerQuad = 32, kQuadMetres = 1000;
  const double by_samples = quads / kSamplesPerQuad, by_metres = h.extent() / kQuadMetres;
  const int most = std::max(1, quads / 8);
  return std::min({quads, most > 16 ? most : 16,
                   std::max(16, int(std::lround(std::max(by_samples, by_metres))))});
}

RenderStack make_render_stack(const Terrain& terrain, const RenderStackOptions& o) {
  if (o.warp && !(o.warp_margin >= 0 && o.warp_margin <= 1))
    throw InputError(fmt::format("warp_margin {}: must be within 0..1", o.warp_margin));
  RenderStack s;
  // With a warp the real renderer draws a margin around the image (a wider
  // field of view at the same pixel density) that the warp can read.
  if (o.warp) {
    s.margin_x = int(std::lround(o.warp_margin * o.width));
    s.margin_y = int(std::lround(o.warp_margin * o.height));
  }
  const int w = o.width + 2 * s.margin_x, h = o.height + 2 * s.margin_y;
  switch (o.mode) {
    case RenderMode::kFull:
    case RenderMode::kLod:
      add_mesh_renderer(s, terrain, o, w, h);
      break;
    case RenderMode::kSprite:
      add_sprite_renderer(s, terrain, o, w, h);
      break;
    case RenderMode::kVoxel:
      add_voxel_renderer(s, terrain, o, w, h);
      break;
  }
  if (o.warp) {
    WarpScheduleOptions so;
    so.real_every = o.real_every;
    so.margin_x = s.margin_x;
    so.margin_y = s.margin_y;
    so.warp.method = *o.warp;
    s.warp = std::make_unique<WarpScheduler>(*s.real, o.width, o.height, so);
  }
  return s;
}

}  // namespace terrasprite
