// SPDX-License-Identifier: MIT
// CPU voxel ray casting of the height field (Cohen-Or, Rich, Lerner, Shenkar,
// "A real-time photo-realistic visual flythrough"): vertical-plane ray
// coherence, a multiresolution height/colour pyramid, a max-height pyramid for
// the first hit, and a parallel pool of columns. Plus a slow, supersampled
// per-pixel reference renderer for quality ground truth.
#pragma once
#include <memory>
#include <string>

#include "terrasprite/camera/renderer.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/terrain_tiles.h"

namespace terrasprite {

/// The terrain as the ray casters read it: a pyramid of heights (metres) and
/// colours (the drape texture box-filtered onto the height grid, then halved
/// level by level), and a max-height pyramid. Built once from a Terrain and
/// read-only afterwards, so any number of renderers and threads can share it.
/// A height field narrower than 2 samples on a side has no area: every ray
/// leaves it (sky). Memory: about 16 bytes per height sample (both pyramids).
/// As TerrainTiles: levels 0..levels()-1, every tile resident for the
/// object's lifetime, 128-cell tiles viewing the pyramids in place.
class VoxelTerrain : public TerrainTiles {
 public:
  explicit VoxelTerrain(const Terrain& terrain);
  ~VoxelTerrain() override;
  VoxelTerrain(const VoxelTerrain&) = delete;
  VoxelTerrain& operator=(const VoxelTerrain&) = delete;

  int levels() const;  ///< pyramid levels, >= 1 (level 0 = full resolution)
  const TerrainGrid& grid() const override;
  const TileBlock* tile(int level, int tx, int ty) const override;
  const TileBlock* level_block(int level) const override;  ///< every level: one block
  struct Data;
  const Data& data() const { return *d_; }

 private:
  std::unique_ptr<Data> d_;
};

enum class VoxelVariant {
  kNaive,     ///< per-pixel marching at full resolution: the baseline
  kCoherent,  ///< vertical-plane coherence + max-pyramid first hit, one level
  kMultires,  ///< coherence + multiresolution traversal with level blending (default)
};

/// "naive", "coherent", "multires"; throws InputError naming `text` otherwise.
VoxelVariant parse_voxel_variant(const std::string& text);
const char* to_string(VoxelVariant v);

struct VoxelOptions {
  VoxelVariant variant = VoxelVariant::kMultires;
  /// Multires: the traversal coarsens (doubling its step) where one voxel of
  /// the current level would cover less than this many pixels. 1 is the
  /// paper's rule (a voxel narrower than a pixel); larger is faster and
  /// blurrier, smaller sharper and slower. > 0.
  double pixel_voxel_ratio = 1.0;
  bool blend_levels = true;  ///< morph heights and colours towards the next level by distance
  bool max_skip = true;      ///< skip empty space with the max-height pyramid (coherent, multires)
  /// Intermediate-buffer samples per output pixel along each vertical plane
  /// and across planes (at the plane's far end). 1 keeps the cost near one
  /// ray per pixel; 2 sharpens the resampled image at about 4x the rays.
  double plane_oversample = 1.0;
  int threads = 0;  ///< worker threads; 0 = all hardware threads
};

/// The ray caster. Renders `width` x `height` frames of the camera view of
/// `terrain` (which must outlive it; read through its tiles, falling back to
/// a coarser level where a tile is not resident): colour, and depth in metres along the
/// view axis (+inf where a ray leaves the terrain: sky colour kSkyColor).
/// Conventions are the Camera's, so images register with the GL renderers.
/// Rays see the height field's top surface only (no skirts, no near/far
/// clipping): a ray entering the grid's side below its edge passes under it.
/// An eye below the surface sees the ground colour under it at depth 0.
class VoxelRenderer : public Renderer {
 public:
  VoxelRenderer(const TerrainTiles& terrain, int width, int height, VoxelOptions options = {});
  ~VoxelRenderer() override;
  /// Draws colour and depth straight into the returned Frame (CPU memory).
  Frame draw(const Camera& camera) override;
  /// As draw(), into `target`: its colour and depth buffers are kept when
  /// they already hold width x height pixels (every pixel is overwritten, so
  /// nothing is cleared), else replaced.
  void draw_into(const Camera& camera, Frame& target) override;
  /// Nothing to copy: draw() already filled colour and depth.
  void read_back(Frame&, ReadBack) override {}
  std::string name() const override;
  const VoxelOptions& options() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

struct ReferenceOptions {
  int supersample = 2;       ///< n x n rays per pixel (1..8)
  double step_cells = 0.25;  ///< marching step, in height-grid cells
  int threads = 0;           ///< 0 = all hardware threads
};

/// Ground truth: per-pixel ray marching with small steps, the exact bilinear
/// height surface (crossings refined by bisection), full-resolution colour,
/// n x n supersampling. Slow by design. Depth is the mean over the pixel's
/// rays that hit (+inf when none does).
class VoxelReference : public Renderer {
 public:
  VoxelReference(const VoxelTerrain& terrain, int width, int height, ReferenceOptions options = {});
  ~VoxelReference() override;
  /// Draws colour and depth straight into the returned Frame (CPU memory).
  Frame draw(const Camera& camera) override;
  /// Nothing to copy: draw() already filled colour and depth.
  void read_back(Frame&, ReadBack) override {}
  std::string name() const override;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace terrasprite
