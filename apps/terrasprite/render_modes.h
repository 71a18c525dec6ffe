// SPDX-License-Identifier: MIT
// The sprite's coarse-mesh options (`--mesh`, `--mesh-triangles`), parsed.
// The modes themselves and their renderers: terrasprite/experiment/render_mode.h
// and render_stack.h.
#pragma once
#include <string>

#include "terrasprite/experiment/render_mode.h"
#include "terrasprite/experiment/render_stack.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite::cli {

/// "uniform" | "adaptive" -> the sprite's coarse mesh; throws InputError naming --mesh.
CoarseMesh parse_mesh(const std::string& text);
/// --mesh-triangles: 0 (the uniform grid's) or at least 2; throws InputError naming it.
void check_mesh_triangles(long long triangles);

}  // namespace terrasprite::cli
