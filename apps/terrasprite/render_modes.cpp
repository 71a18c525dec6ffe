// SPDX-License-Identifier: MIT
#include "render_modes.h"

#include <fmt/format.h>

#include <algorithm>
#include <thread>

#include "cli_common.h"
#include "terrasprite/common/error.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite::cli {

CoarseMesh parse_mesh(const std::string& text) {
  if (text == "uniform") return CoarseMesh::kUniform;
  if (text == "adaptive") return CoarseMesh::kAdaptive;
  throw InputError(fmt::format("--mesh {}: must be 'uniform' or 'adaptive'", text));
}

void check_mesh_triangles(long long triangles) {
  if (triangles != 0 && triangles < 2)
    throw InputError(fmt::format(
        "--mesh-triangles {}: must be 0 (the uniform grid's 2 x lod-quads^2) or at least 2",
        triangles));
}

std::vector<std::string> render_modes() {
  return {"full", "lod", "sprite", "voxel"};
}

RenderStack make_render_stack(const std::string& mode, const Terrain& terrain, int width,
                              int height, int lod_quads, bool lighting, double sprite_threshold_px,
                              GlContext* context, bool async_keyframes, CoarseMesh sprite_mesh,
                              long long sprite_mesh_triangles) {
  RenderStack s;
  // GL modes: the caller's current context, else one of our own.
  auto use_gl = [&] {
    if (!context) s.gl = std::make_unique<GlContext>();
    s.device = (context ? context : s.gl.get())->renderer();
  };
  if (mode == "full" || mode == "lod") {
    if (mode == "lod") check_lod_quads(lod_quads, terrain.heights);
    use_gl();
    s.scene = std::make_unique<Scene>(terrain);
    s.renderer = std::make_unique<MeshRenderer>(
        *s.scene, width, height, mode == "full" ? 0 : lod_quads, RasterOptions{lighting});
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
    check_lod_quads(lod_quads, terrain.heights);
    SpriteOptions o;
    o.lod_quads = lod_quads;
    o.threshold_px = sprite_threshold_px;
    o.lighting = lighting;
    o.mesh = sprite_mesh;
    o.mesh_triangles = sprite_mesh_triangles;
    use_gl();
    if (async_keyframes) {
      o.async_context = context ? context : s.gl.get();
      o.async_first_keyframe = true;  // a mode or threshold switch never waits for a keyframe
    }
    s.scene = std::make_unique<Scene>(terrain);
    s.renderer = std::make_unique<SpriteRenderer>(*s.scene, width, height, o);
    return s;
  }
  throw InputError(fmt::format("--mode {}: unknown mode", mode));
}

}  // namespace terrasprite::cli
