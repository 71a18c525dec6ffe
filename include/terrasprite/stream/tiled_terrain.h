// SPDX-License-Identifier: MIT
// A terrain pyramid on disk as Cloud-Optimized GeoTIFFs: the ray caster's own
// vertex-aligned levels (see TerrainGrid) written as each file's overviews,
// so a reader fetches any tile of any level with one windowed read.
//
//   DIR/height.tif  Float32 heights, level 0 + levels 1.. as overviews
//   DIR/color.tif   Byte RGB, the same levels
//   DIR/bound.tif   Float32 max-height bounds per cell, bound levels as overviews
//   DIR/tiles.json  grid, levels, per-tile max-height bounds, georeferencing
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/common/image.h"
#include "terrasprite/stream/insets.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/terrain_tiles.h"

namespace terrasprite {

struct TileSetInfo;

/// High-resolution insets stored as sparse levels finer than a base's level 0
/// (`tile --inset FILE --fine-levels K`): a tile set of its own (DIR/fine)
/// over a window of the fine grid (spacing base / 2^K), whose tiles are
/// handed out as levels 0..K-1 of the combined grid; the base's levels
/// become K.. (see combined_grid).
struct FineLevelsInfo {
  int levels = 0;                  ///< K
  int origin_x = 0, origin_y = 0;  ///< the window's sample (0, 0) in the fine grid
  /// Per fine level, per tile of the window set: 1 where the tile holds inset
  /// data (blend weight > 0 within its filter's reach); absent tiles are not
  /// read, the base serves them. Row-major, the window set's tile tables.
  std::vector<std::vector<std::uint8_t>> present;
  /// Writing only: per base level-0 cell (row-major, (W-1) x (H-1)), the
  /// highest fine sample in it (-inf where none): raises the base's bounds
  /// so empty-space skipping never steps over inset detail.
  std::vector<float> base_cell_max;
};

/// How `write_tiled_terrain` encodes the files.
struct TileWriteOptions {
  int tile_log2 = 7;                        ///< tiles of 2^tile_log2 cells (4..9: 16..512)
  std::string color_compress = "JPEG";      ///< JPEG, WEBP or DEFLATE (lossless)
  int color_quality = 90;                   ///< JPEG / WEBP quality, 1..100
  std::string height_compress = "DEFLATE";  ///< DEFLATE or ZSTD, with PREDICTOR=3
  std::vector<InsetResult> insets;          ///< composited into the terrain: recorded in tiles.json
  std::optional<FineLevelsInfo> fine;       ///< sparse finer levels already written to DIR/fine
};

struct CogInput;  // an existing COG read in place (see open_cog)

/// What tiles.json says: the grid and the per-tile max-height bounds. For an
/// existing COG (open_cog), `dir` is the COG's path and `cog` is set.
struct TileSetInfo {
  std::string dir;
  std::shared_ptr<const CogInput> cog;
  TerrainGrid grid;  ///< finest_level 0, coarsest_level, bound_levels, tile_log2
  /// Per bound level: tiles across and down, and each tile's max height
  /// (row-major, metres): every sample and cell bound of the tile is below it.
  std::vector<int> tiles_x, tiles_y;
  std::vector<std::vector<float>> tile_max;
  std::optional<GeoTransform> geo;
  long long bytes_on_disk = 0;  ///< the three .tif files (a COG: it and its texture; + fine)
  /// Sparse finer levels (insets) and their tile set, when tiles.json has them.
  std::optional<FineLevelsInfo> fine;
  std::shared_ptr<const TileSetInfo> fine_set;
  /// A fine window set's own: its level-0 sample (0, 0) is sample (origin_x,
  /// origin_y) of the enclosing fine grid, and the tiles it hands out (via
  /// TileFile::read, ResidentTiles) use the enclosing grid's indices.
  int origin_x = 0, origin_y = 0;
  /// Per level, 1 where a tile holds data (empty: every tile; a fine set's).
  std::vector<std::vector<std::uint8_t>> present;
  bool tile_present(int level, int tx, int ty) const {
    return std::size_t(level) >= present.size() ||
           present[std::size_t(level)][std::size_t(ty) * std::size_t(tiles_x[std::size_t(level)]) +
                                       std::size_t(tx)] != 0;
  }

  std::string height_file() const { return dir + "/height.tif"; }
  std::string color_file() const { return dir + "/color.tif"; }
  std::string bound_file() const { return dir + "/bound.tif"; }
  /// Samples (or, past coarsest_level, cells + 1) of `level` along x / y.
  int level_w(int level) const { return tiles_cells_w(level) + 1; }
  int level_h(int level) const { return tiles_cells_h(level) + 1; }
  int tiles_cells_w(int level) const;  ///< cells of `level` along x (bound grid)
  int tiles_cells_h(int level) const;
};

/// The grid a renderer sees: `set.grid` itself, or with fine levels K the
/// combined grid: 2^K times denser, levels 0..K-1 sparse inside the fine
/// window (TerrainGrid::sparse_levels), the base's levels as K...
TerrainGrid combined_grid(const TileSetInfo& set);
/// The world offset (metres) of a fine window set's own frame: world =
/// its own world position + (x, y).
void fine_world_shift(const TileSetInfo& set, double& x, double& y);

/// Writes `terrain`'s pyramids (heights and colours of levels
/// 0..coarsest_level, bounds of levels 0..bound_levels-1) into the partial
/// output directory `dir` (it must exist): height.tif, color.tif, bound.tif
/// as COGs, then tiles.json. `terrain` must hold every level whole
/// (TerrainTiles::level_block, rows packed), as an in-memory pyramid does;
/// std::invalid_argument otherwise. `geo` (optional) georeferences level 0.
/// Throws InputError for a terrain without area, or naming a file GDAL could
/// not write. Memory: the files are written from the pyramid in place (GDAL
/// reads it through MEM datasets), plus GDAL's block cache.
void write_tiled_terrain(const TerrainTiles& terrain, const std::optional<GeoTransform>& geo,
                         const std::string& dir, const TileWriteOptions& options = {});

/// Level-0 rows of a terrain too large to hold, produced on demand for
/// write_tiled_terrain_strips.
struct TerrainRows {
  int width = 0, height = 0;                ///< samples (>= 2 each)
  double spacing_x = 1.0, spacing_y = 1.0;  ///< metres between samples
  float min_height = 0, max_height = 0;     ///< over every sample, metres
  /// Writes row j's heights (metres) and packed RGBA8 colours, `width` each.
  /// Called concurrently for different rows.
  std::function<void(int j, float* heights, std::uint32_t* colors)> row;
};

/// The final grid of `terrain` (views it: it must outlive the result), its
/// colour the drape texture box-filtered onto the samples as the ray
/// caster's in-memory pyramid does.
TerrainRows terrain_rows(const LargeTerrain& terrain);

/// Where write_tiled_terrain_strips spent its time, seconds.
struct StripWriteStats {
  double pyramid_s = 0;      ///< level 0 generated, every level and bound to temporary files
  double cogs_s = 0;         ///< the three COGs copied from them
  long long temp_bytes = 0;  ///< the temporary files' size (removed at the end)
  int band_rows = 0;         ///< level-0 rows generated at once
};

/// write_tiled_terrain without holding the terrain: the same files, equal
/// sample for sample (the same pyramid arithmetic, row by row). Level 0 is
/// generated in bands of rows; every render level and bound level is built
/// from the one below as its rows arrive (three rows of the finer level
/// held each) and written to a tiled temporary GeoTIFF in DIR/.strips,
/// copied into the COGs at the end and then removed. Memory: a band of
/// level 0 (band_rows x width x 8 bytes), a few rows per level, GDAL's
/// block cache; disk: about 12 bytes a level-0 sample of temporary files.
/// `options.fine` and `options.insets` must be empty (insets composite into
/// a grid held in memory). `band_rows`: level-0 rows made at once, a
/// multiple of the tile size (0: about 64 MB of them, at most 1024 rows).
/// Throws InputError as write_tiled_terrain.
StripWriteStats write_tiled_terrain_strips(const TerrainRows& rows,
                                           const std::optional<GeoTransform>& geo,
                                           const std::string& dir,
                                           const TileWriteOptions& options = {}, int band_rows = 0);

/// Reads DIR/tiles.json and checks that the three files exist and open as
/// rasters of the stated sizes. Throws InputError naming the file otherwise.
TileSetInfo read_tile_set(const std::string& dir);

/// An existing Cloud-Optimized GeoTIFF (or any tiled single-band GeoTIFF with
/// overviews) as a tiled terrain, read in place. Its overviews are
/// area-aligned (GDAL's), so level L's vertex-aligned sample i (level-0 index
/// i 2^L) is read bilinearly from the coarsest overview of factor <= 2^L at
/// that overview's pixel-centre coordinate (i 2^L + 0.5) / f - 0.5. The
/// max-height bounds are computed here in one pass over the raster and its
/// overviews (strips, never the whole raster). `texture` (optional) is an RGB
/// raster of the same size; without one the terrain is grey. Throws
/// InputError naming the file when it cannot be read, has no overviews, is
/// not tiled, has more than one band, or has nodata samples. Tiles are
/// 2^tile_log2 cells; 0: the COG's own blocks when square, 16..512 (else 128).
/// Bound levels are
/// held from the first whose cells number at most `held_bound_cells`; finer
/// ones repeat the held cell holding each cell (looser, still bounds).
TileSetInfo open_cog(const std::string& path, const std::string& texture = {}, int tile_log2 = 0,
                     long long held_bound_cells = 1 << 22);

/// `--tiles DIR` or `--cog FILE [--texture FILE]`, exactly one of the two.
TileSetInfo open_tile_source(const std::string& tiles, const std::string& cog,
                             const std::string& texture);

}  // namespace terrasprite
