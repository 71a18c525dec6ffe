// SPDX-License-Identifier: MIT
#include "render_modes.h"

#include <fmt/format.h>

#include "terrasprite/error.h"
#include "terrasprite/sprite_renderer.h"

namespace terrasprite::cli {

std::vector<std::string> render_modes() { return {"full", "lod", "sprite"}; }

RenderStack make_render_stack(const std::string& mode, const Terrain& terrain, int width, int height, int lod_quads) {
  RenderStack s;
  if (mode == "full" || mode == "lod") {
    if (mode == "lod" && lod_quads < 1) throw InputError(fmt::format("--lod-quads {}: must be at least 1", lod_quads));
    s.gl = std::make_unique<GlContext>();
    s.device = s.gl->renderer();
    s.scene = std::make_unique<GlTerrain>(terrain);
    s.renderer = std::make_unique<MeshRenderer>(*s.scene, width, height, mode == "full" ? 0 : lod_quads);
    return s;
  }
  if (mode == "sprite") {
    SpriteOptions o;
    o.lod_quads = lod_quads;
    o.read_depth = true;
    s.gl = std::make_unique<GlContext>();
    s.device = s.gl->renderer();
    s.scene = std::make_unique<GlTerrain>(terrain);
    s.renderer = std::make_unique<SpriteRenderer>(*s.scene, width, height, o);
    return s;
  }
  throw InputError(fmt::format("--mode {}: unknown mode", mode));
}

}  // namespace terrasprite::cli
