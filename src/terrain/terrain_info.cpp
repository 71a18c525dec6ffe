// SPDX-License-Identifier: MIT
#include "terrasprite/terrain/terrain_info.h"

namespace terrasprite {

TerrainInfo terrain_info(const Terrain& t) {
  const Heightfield& h = t.heights;
  return {h.name,      t.texture_name, h.width,        h.height,        h.spacing_x,
          h.spacing_y, h.min_height(), h.max_height(), h.resampled_from};
}

}  // namespace terrasprite
