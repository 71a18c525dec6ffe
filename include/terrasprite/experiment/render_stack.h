// SPDX-License-Identifier: MIT
// The renderer a RenderMode names, with what it needs (GL context,
// GPU-resident terrain or voxel pyramids) and, optionally, a post-render warp
// between real frames (Cohen-Or et al.'s video-rate scheme): assembled here
// once for `render`, `view` and the benches, owned together and destroyed in
// the right order.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "terrasprite/camera/renderer.h"
#include "terrasprite/experiment/render_mode.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "terrasprite/warp/warp_renderer.h"

namespace terrasprite {

/// The margin a warped stack's real frames are drawn with by default, as a
/// fraction of the output width (height) on each side.
inline constexpr double kDefaultWarpMargin = 0.05;

struct RenderStackOptions {
  RenderMode mode = RenderMode::kFull;
  int width = 512, height = 512;  ///< the frames the stack returns, pixels
  int lod_quads = 16;             ///< lod and sprite: coarse grid quads per side
  bool lighting = false;          ///< GL modes: sun lighting on top of the texture
  /// sprite: the keyframe threshold (pixels), its coarse mesh and that mesh's
  /// triangle budget (0: the uniform grid's).
  double sprite_threshold_px = 1.0;
  CoarseMesh sprite_mesh = CoarseMesh::kUniform;
  long long sprite_mesh_triangles = 0;
  /// sprite: keyframes drawn on a second thread in a context shared with the
  /// stack's (SpriteOptions::async_context).
  bool async_keyframes = false;
  /// GL modes: a context current on the calling thread to draw with instead
  /// of creating one (e.g. the viewer's, sharing objects with its window);
  /// not owned, must outlive the stack. Null: the stack creates its own.
  GlContext* context = nullptr;
  /// voxel: VoxelOptions::pixel_voxel_ratio, and pyramids to share (not
  /// owned, must outlive the stack); null: built from the terrain and owned.
  double voxel_ratio = 1.0;
  const VoxelTerrain* voxels = nullptr;
  /// Set: every real_every-th frame is rendered for real, with a margin of
  /// warp_margin x (width, height) pixels on each side (rounded), and the
  /// frames between are warped from it with this method.
  std::optional<WarpMethod> warp;
  int real_every = 4;
  double warp_margin = kDefaultWarpMargin;
};

struct RenderStack {
  std::unique_ptr<GlContext> gl;        ///< null for CPU renderers or a caller's context
  std::unique_ptr<Scene> scene;         ///< null for CPU renderers
  std::unique_ptr<VoxelTerrain> voxel;  ///< the voxel renderer's own pyramids, else null
  std::unique_ptr<Renderer> real;       ///< the mode's renderer, drawing with the margins
  std::unique_ptr<WarpScheduler> warp;  ///< with a warp, else null; destroyed first
  int margin_x = 0, margin_y = 0;       ///< pixels each side of the real frames (0 without warp)
  std::string device;                   ///< GL_RENDERER, or the CPU renderer's description
  /// The stack's renderer: the warp schedule when there is one, else the real renderer.
  Renderer& renderer() { return warp ? static_cast<Renderer&>(*warp) : *real; }
};

/// Builds the stack for `options` over `terrain`, which must outlive it.
/// The default coarse grid of the lod and sprite modes for `h`, quads per
/// side: a quad of about 32 samples or 1 km, whichever is finer, at least 16
/// quads (the paper setup on its 513-sample terrain) and at most one quad per
/// 8 samples of the shorter side.
int auto_lod_quads(const Heightfield& h);

/// Throws InputError naming lod_quads when a lod or sprite grid does not fit
/// the terrain, or naming warp_margin or real_every when out of range;
/// DeviceError when a GL mode finds no GL device.
RenderStack make_render_stack(const Terrain& terrain, const RenderStackOptions& options);

}  // namespace terrasprite
