// SPDX-License-Identifier: MIT
// tiles.json: the grid, the levels and the per-tile max-height bounds of a
// tiled terrain (see terrasprite/stream/tiled_terrain.h).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite {

/// Per bound level of `grid`, the highest bound of each tile of
/// 2^tile_log2 cells (row-major tiles); `bounds` (one per bound level,
/// row-major cells) are the bounds written to bound.tif.
std::vector<std::vector<float>> tile_maxima(const TerrainGrid& grid,
                                            const std::vector<const float*>& bounds, int tile_log2);

/// The grid, levels, fine levels and georeferencing `text` (a tiles.json named
/// `path` in messages) describes, every value checked; the rasters beside it
/// are not opened (read_tile_set does that). Throws InputError naming `path`.
TileSetInfo parse_tile_set_json(const std::string& text, const std::string& path);

/// Writes `path` (tiles.json) for a terrain of `grid` tiled with `options`;
/// `tile_max` as tile_maxima's.
void write_tile_set_json(const TerrainGrid& grid, const std::vector<std::vector<float>>& tile_max,
                         const std::optional<GeoTransform>& geo, const TileWriteOptions& options,
                         const std::string& path);

}  // namespace terrasprite
