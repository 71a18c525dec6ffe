// SPDX-License-Identifier: MIT
// Builds the renderer a `--mode` names, with what it needs (GL context,
// GPU-resident terrain), owned together and destroyed in the right order.
#pragma once
#include <memory>
#include <string>

#include "terrasprite/gl/gl_context.h"
#include "terrasprite/camera/renderer.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite::cli {

struct RenderStack {
  std::unique_ptr<GlContext> gl;        // null for CPU renderers
  std::unique_ptr<Scene> scene;         // null for CPU renderers
  std::unique_ptr<VoxelTerrain> voxel;  // the voxel renderer's pyramids, else null
  std::unique_ptr<Renderer> renderer;   // destroyed first
  std::string device;                   // GL_RENDERER, or the CPU renderer's description
};

/// Modes: full, lod, sprite (LOD-sprite with default SpriteOptions and `lod_quads`), voxel
/// (CPU, all cores). Throws InputError for an unknown mode, DeviceError when a GL mode finds no
/// GL device. `terrain` must outlive the stack. `sprite_threshold_px`: the
/// LOD-sprite keyframe threshold. `context` (may be null): a GL context current
/// on the calling thread that the stack draws with instead of creating its
/// own (e.g. the viewer's context sharing objects with its window); it must
/// outlive the stack. `async_keyframes`: sprite draws its keyframes on a second
/// thread in a context shared with the stack's (SpriteOptions::async_context).
RenderStack make_render_stack(const std::string& mode, const Terrain& terrain, int width,
                              int height, int lod_quads, bool lighting = false,
                              double sprite_threshold_px = 1.0, GlContext* context = nullptr,
                              bool async_keyframes = false,
                              CoarseMesh sprite_mesh = CoarseMesh::kUniform,
                              long long sprite_mesh_triangles = 0);

/// "uniform" | "adaptive" -> the sprite's coarse mesh; throws InputError naming --mesh.
CoarseMesh parse_mesh(const std::string& text);
/// --mesh-triangles: 0 (the uniform grid's) or at least 2; throws InputError naming it.
void check_mesh_triangles(long long triangles);

/// The modes make_render_stack accepts, for CLI11's check.
std::vector<std::string> render_modes();

}  // namespace terrasprite::cli
