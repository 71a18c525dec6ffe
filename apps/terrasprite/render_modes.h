// SPDX-License-Identifier: MIT
// Builds the renderer a `--mode` names, with what it needs (GL context,
// GPU-resident terrain), owned together and destroyed in the right order.
#pragma once
#include <memory>
#include <string>

#include "terrasprite/gl_context.h"
#include "terrasprite/mesh_renderer.h"
#include "terrasprite/renderer.h"
#include "terrasprite/voxel_renderer.h"

namespace terrasprite::cli {

struct RenderStack {
  std::unique_ptr<GlContext> gl;        // null for CPU renderers
  std::unique_ptr<GlTerrain> scene;     // null for CPU renderers
  std::unique_ptr<VoxelTerrain> voxel;  // the voxel renderer's pyramids, else null
  std::unique_ptr<Renderer> renderer;   // destroyed first
  std::string device;                   // GL_RENDERER, or the CPU renderer's description
};

/// Modes: full, lod, sprite (LOD-sprite with default SpriteOptions and `lod_quads`), voxel
/// (CPU, all cores). Throws InputError for an unknown mode, DeviceError when a GL mode finds no
/// GL device. `terrain` must outlive the stack. `read_depth` off: colour only
/// (the viewer); `sprite_threshold_px`: the LOD-sprite keyframe threshold.
RenderStack make_render_stack(const std::string& mode, const Terrain& terrain, int width,
                              int height, int lod_quads, bool lighting = false,
                              bool read_depth = true, double sprite_threshold_px = 1.0);

/// The modes make_render_stack accepts, for CLI11's check.
std::vector<std::string> render_modes();

}  // namespace terrasprite::cli
