// SPDX-License-Identifier: MIT
// tiles.json: the grid, the levels and the per-tile max-height bounds of a
// tiled terrain (see terrasprite/tiled_terrain.h).
#pragma once
#include <optional>
#include <string>

#include "terrasprite/tiled_terrain.h"

namespace terrasprite {

/// Writes `path` (tiles.json) for `terrain` tiled with `options`.
void write_tile_set_json(const VoxelTerrain& terrain, const std::optional<GeoTransform>& geo,
                         const TileWriteOptions& options, const std::string& path);

}  // namespace terrasprite
