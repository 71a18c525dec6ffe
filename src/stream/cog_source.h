// SPDX-License-Identifier: MIT
// An existing COG read in place as a tiled terrain (see open_cog in
// terrasprite/stream/tiled_terrain.h): overview selection, the area-aligned to
// vertex-aligned resampling of a tile, and the max-height bounds computed
// once at open.
#pragma once
#include <string>
#include <vector>

#include "stream/tile_file.h"
#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite {

struct CogInput {
  std::string path, texture;  ///< texture: "" when the terrain is grey
  struct Raster {
    int w = 0, h = 0;
  };
  /// The rasters a level may read: [0] the full raster, [k] overview k - 1.
  std::vector<Raster> height_rasters, texture_rasters;
  /// Bound levels bound_from.. are held here (dilated max-height bounds per
  /// cell, row-major, TileSetInfo::tiles_cells_w(L) wide); finer bound levels
  /// repeat the bound of the bound_from cell holding each cell (looser, still
  /// a bound).
  int bound_from = 0;
  std::vector<std::vector<float>> bound;
  double bounds_ms = 0;  ///< the one pass that computed them (or the cache read)
  /// Read back from the bounds cache (stream/cog_bounds_cache.h), not computed.
  bool bounds_cached = false;
};

/// The raster (0: full, k: overview k - 1) level `level` reads: the coarsest
/// whose reduction factor along both axes is at most 2^level (1% slack for
/// GDAL's rounding of odd sizes).
int cog_raster_for_level(const std::vector<CogInput::Raster>& rasters, int level);

/// Reads the window of level `level` (samples x0.., y0.., w x h) from the COG
/// (and texture when `texture` is set) into `out`'s height, colour and bound
/// vectors (block views are the caller's). False and `error` set on failure.
bool read_cog_window(const TileSetInfo& set, GDALDatasetH height, GDALDatasetH texture, int level,
                     int x0, int y0, int w, int h, TileData& out, std::string& error);

}  // namespace terrasprite
