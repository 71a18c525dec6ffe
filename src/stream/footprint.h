// SPDX-License-Identifier: MIT
// The tiles a camera will read (Cohen-Or et al.'s extended footprint): at
// each level, the tiles in the distance band where the ray caster reads that
// level, inside the horizontal view wedge, both grown by a margin, from the
// camera's position and from where its motion takes it next.
#pragma once
#include <glm/vec3.hpp>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite {

struct TileKey {
  int level = 0, tx = 0, ty = 0;
  double priority = 0;  ///< smaller first: distance over the level's reach
};

struct FootprintOptions {
  double margin = 1.5;
  double lookahead_frames = 30;
  double pixel_voxel_ratio = 1.0;
  int image_height = 1080;
  int levels = 0;  ///< levels 0..levels-1 (the unpinned ones)
};

/// Appends the footprint's tiles of `camera`, moving `motion` metres per
/// frame, to `out` (a tile may appear twice: once per position).
void footprint(const TileSetInfo& set, const Camera& camera, const glm::dvec3& motion,
               const FootprintOptions& options, std::vector<TileKey>& out);

/// The reach of level `level` (metres from the eye where the ray caster
/// stops reading it), for the camera's pixel angle and the voxel ratio.
double level_reach(const TileSetInfo& set, const Camera& camera, const FootprintOptions& options,
                   int level);

/// Horizontal distance (metres) from world point (x, y) to tile (tx, ty) of `level`.
double tile_distance(const TileSetInfo& set, int level, int tx, int ty, double x, double y);

}  // namespace terrasprite
