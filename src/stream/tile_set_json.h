// SPDX-License-Identifier: MIT
// tiles.json: the grid, the levels and the per-tile max-height bounds of a
// tiled terrain (see terrasprite/tiled_terrain.h).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/tiled_terrain.h"

namespace terrasprite {

/// Writes `path` (tiles.json) for `terrain` tiled with `options`; `bounds`
/// (one per bound level, row-major cells) are the bounds written to bound.tif.
void write_tile_set_json(const VoxelTerrain& terrain, const std::vector<const float*>& bounds,
                         const std::optional<GeoTransform>& geo, const TileWriteOptions& options,
                         const std::string& path);

}  // namespace terrasprite
