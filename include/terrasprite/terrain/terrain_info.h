// SPDX-License-Identifier: MIT
// What a report says of a terrain: a copy of its name, grid and height range
// that outlives the Terrain (a study's result carries it to the report).
#pragma once
#include <optional>
#include <string>
#include <utility>

#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

struct TerrainInfo {
  std::string name, texture;
  int samples_x = 0, samples_y = 0;
  double spacing_x = 0, spacing_y = 0;    ///< metres
  double height_min = 0, height_max = 0;  ///< metres
  /// The source's samples when the heights were resampled (--resample); none
  /// when the grid is the input as given.
  std::optional<std::pair<int, int>> resampled_from;
};

TerrainInfo terrain_info(const Terrain& t);

}  // namespace terrasprite
