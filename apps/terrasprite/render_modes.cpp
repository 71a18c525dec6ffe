// SPDX-License-Identifier: MIT
#include "render_modes.h"

#include <fmt/format.h>

#include <algorithm>
#include <thread>

#include "terrasprite/error.h"
#include "terrasprite/sprite_renderer.h"

namespace terrasprite::cli {

std::vector<std::string> render_modes() {
  return {"full", "lod", "sprite", "voxel"};
}

RenderStack make_render_stack(const std::string& mode, const Terrain& terrain, int width,
                              int height, int lod_quads, bool lighting, bool read_depth,
                              double sprite_threshold_px) {
  RenderStack s;
  if (mode == "full" || mode == "lod") {
    if (mode == "lod" && lod_quads < 1)
      throw InputError(fmt::format("--lod-quads {}: must be at least 1", lod_quads));
    s.gl = std::make_unique<GlContext>();
    s.device = s.gl->renderer();
    s.scene = std::make_unique<GlTerrain>(terrain);
    s.renderer = std::make_unique<MeshRenderer>(
        *s.scene, width, height, mode == "full" ? 0 : lod_quads, RasterOptions{lighting, read_depth});
    return s;
  }
  if (mode == "voxel") {
    s.voxel = std::make_unique<VoxelTerrain>(terrain);
    auto owned = std::make_unique<VoxelRenderer>(*s.voxel, width, height);
    VoxelRenderer* r = owned.get();
    s.renderer = std::move(owned);
    s.device = fmt::format("cpu voxel {}, {} threads", to_string(r->options().variant),
                           std::max(1u, std::thread::hardware_concurrency()));
    return s;
  }
  if (mode == "sprite") {
    SpriteOptions o;
    o.lod_quads = lod_quads;
    o.read_depth = read_depth;
    o.threshold_px = sprite_threshold_px;
    s.gl = std::make_unique<GlContext>();
    s.device = s.gl->renderer();
    s.scene = std::make_unique<GlTerrain>(terrain);
    s.renderer = std::make_unique<SpriteRenderer>(*s.scene, width, height, o);
    return s;
  }
  throw InputError(fmt::format("--mode {}: unknown mode", mode));
}

}  // namespace terrasprite::cli
