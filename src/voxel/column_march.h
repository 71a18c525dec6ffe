// SPDX-License-Identifier: MIT
// Marching the rays of one vertical plane through the eye over the height
// field, bottom ray first (Cohen-Or et al., "vertical ray coherence").
#pragma once
#include <cstdint>
#include <span>

#include "terrasprite/voxel/terrain_tiles.h"

namespace terrasprite {

/// What a march needs that is fixed for a frame.
struct MarchSettings {
  bool multires = true;       // coarsen with distance (else level 0 only)
  bool blend = true;          // morph towards the next level by distance
  bool max_skip = true;       // hierarchical empty-space skipping
  double pixel_angle = 1e-3;  // radians per pixel at the image centre
  double ratio = 1.0;         // pixel_voxel_ratio
};

/// A ray's result: horizontal distance to the hit in metres (+inf = left the
/// terrain) and its colour (RGBA8 packed).
struct MarchHit {
  float t;
  std::uint32_t color;
};

/// Marches the rays of the vertical plane through `eye` (world metres) with
/// horizontal direction (dx, dy) (unit). `slopes` (dz per horizontal metre)
/// must be non-decreasing: each ray starts where the one below hit, since a
/// height field cannot hide a nearer hit above it. Writes one hit per slope.
/// The terrain is read through its tiles (levels 0 and coarser); where a tile
/// is not resident the march reads the next coarser level there. `march` may
/// be called from several threads at once.
class ColumnMarcher {
 public:
  ColumnMarcher(const TerrainTiles& terrain, const double eye[3], const MarchSettings& settings);
  void march(double dx, double dy, std::span<const double> slopes, std::span<MarchHit> hits) const;

 private:
  // The march over either reader (tiled, or whole levels without checks),
  // one vertical plane's line and reads at a time (column_march.cpp).
  template <class Reader>
  void march_with(double dx, double dy, std::span<const double> slopes,
                  std::span<MarchHit> hits) const;
  template <class Reader>
  class Plane;

  const TerrainTiles& src_;
  const TerrainGrid& d_;
  MarchSettings s_;
  double eu_, ev_, ez_;  // eye in level-0 grid units (u, v) and metres (z)
  double lift_;          // eye height above the highest terrain (>= 0): bounds 3D distance
  double t1_;            // distance where level 0 ends (level L starts at t1 * 2^(L-1))
  int lmax_;             // coarsest usable level
  bool whole_;           // the source hands out every level whole (in memory)
};

}  // namespace terrasprite
