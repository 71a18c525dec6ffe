// SPDX-License-Identifier: MIT
// What a study's result says of the terrain it ran on: a copy of the figures
// a report prints, so the result outlives the Terrain.
#pragma once
#include <string>

#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

struct TerrainInfo {
  std::string name, texture;
  int samples_x = 0, samples_y = 0;
  double spacing_x = 0, spacing_y = 0;    ///< metres
  double height_min = 0, height_max = 0;  ///< metres
};

/// The terrain's name, texture name, sample counts, spacing and height range.
TerrainInfo terrain_info(const Terrain& t);

}  // namespace terrasprite
