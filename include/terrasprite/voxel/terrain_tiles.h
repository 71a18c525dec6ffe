// SPDX-License-Identifier: MIT
// The terrain as a ray caster reads it: square tiles of a level pyramid of
// heights, colours and max-height bounds, any of which may be missing. The
// in-memory pyramid (VoxelTerrain) answers every tile; a streaming source
// answers the resident ones and lets the caller fall back to a coarser level.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace terrasprite {

/// The sample grid shared by every level, in world units.
///
/// Level 0 is the source height field: `width` x `height` samples,
/// `spacing_x` / `spacing_y` metres apart, centred on the world origin, row 0
/// north (world +y). Sample i of level L sits at level-0 index i * 2^L, so
/// level L has ((n0 - 1 + 2^L - 1) >> L) + 1 samples along a side of n0
/// level-0 samples (the last one repeats the edge). Levels below 0 are finer
/// than the source (high-resolution insets): level -1 has twice the density.
struct TerrainGrid {
  int width = 0, height = 0;                 ///< level-0 samples
  double spacing_x = 1.0, spacing_y = 1.0;   ///< metres between level-0 samples
  float min_height = 0.f, max_height = 0.f;  ///< metres, over the whole terrain
  int finest_level = 0;    ///< <= 0; levels finer than 0 exist only where tiles say so
  int coarsest_level = 0;  ///< the coarsest level with samples (>= 0), always resident
  /// Max-height bounds exist for levels 0..bound_levels-1; the coarsest has
  /// one cell. Bound levels past `coarsest_level` carry bounds only.
  int bound_levels = 1;
  /// Tiles are 2^tile_log2 cells on a side (tile (tx, ty) of a level covers
  /// its cells [tx T, (tx + 1) T) x [ty T, (ty + 1) T), T = 2^tile_log2), and
  /// hold one more sample per side than cells, so bilinear interpolation
  /// inside any cell reads one tile.
  int tile_log2 = 7;
  /// High-resolution insets: levels 0..sparse_levels-1 exist only inside the
  /// box [sparse_x0, sparse_x1] x [sparse_y0, sparse_y1] (level-0 samples),
  /// and there only on tiles that hold inset data; elsewhere the terrain is
  /// level `sparse_levels` (the base's own level 0, 2^sparse_levels times
  /// coarser) and a march reads that level. 0: every level is dense.
  int sparse_levels = 0;
  int sparse_x0 = 0, sparse_y0 = 0, sparse_x1 = -1, sparse_y1 = -1;

  bool has_area() const { return width >= 2 && height >= 2; }
  /// Samples of `level` along a side of n0 level-0 samples (n0 >= 1).
  static int level_size(int n0, int level) {
    if (level < 0) return (n0 - 1) * (1 << -level) + 1;
    return ((n0 - 1 + (1 << level) - 1) >> level) + 1;
  }
  /// Cells of bound level `level` (>= 0) along a side of n0 level-0 samples:
  /// ceil((n0 - 1) / 2^level), and at least one.
  static int bound_cells(int n0, int level) {
    return int((std::int64_t(std::max(1, n0 - 1)) + (std::int64_t(1) << level) - 1) >> level);
  }
  int level_width(int level) const { return level_size(width, level); }
  int level_height(int level) const { return level_size(height, level); }
};

/// One resident tile of one level: views into storage the accessor owns.
///
/// Sample (i, j) of the level (column i, row j), for x0 <= i < x0 + w and
/// y0 <= j < y0 + h, is height[(j - y0) * stride + (i - x0)] (metres) and
/// color[...] at the same index (RGBA8 packed little-endian, alpha 255). A
/// tile at the level's east or south edge is narrower (w, h >= 2 unless the
/// level itself is 1 sample wide). Cell (a, b) (the square between samples
/// (a, b) and (a + 1, b + 1)) has bound[(b - y0) * bound_stride + (a - x0)]:
/// at least every level-0 height in that cell dilated by one cell of this
/// level on each side, so it bounds every level L' <= level - 2 too (whose
/// filters reach less than 2^(L'+2) level-0 samples). `height` and `color` are
/// null on bound-only levels. `max_height` bounds every sample and cell of
/// the tile.
struct TileBlock {
  const float* height = nullptr;
  const std::uint32_t* color = nullptr;
  const float* bound = nullptr;
  std::ptrdiff_t stride = 0;        ///< samples between rows of height / color
  std::ptrdiff_t bound_stride = 0;  ///< cells between rows of bound
  int x0 = 0, y0 = 0;               ///< level index of the first sample / cell
  int w = 0, h = 0;                 ///< samples (cells: w - 1, h - 1; at least 1 each)
  float max_height = 0.f;
};

/// Read access to a terrain, tile by tile. Implementations: VoxelTerrain
/// (everything in memory, always resident); a streaming cache (tiles arrive
/// over time).
///
/// Thread safety: `grid()` and `tile()` may be called concurrently from any
/// number of threads. Ownership: the accessor owns every block; a pointer it
/// returns, and the storage the block views, stay valid and unchanged until
/// the accessor's owner says otherwise (the in-memory pyramid: its lifetime;
/// a streaming cache: until its next between-frames update). Renderers do not
/// keep blocks across frames.
class TerrainTiles {
 public:
  virtual ~TerrainTiles() = default;
  virtual const TerrainGrid& grid() const = 0;
  /// Tile (tx, ty) of `level` (finest_level..bound_levels-1; tx, ty within
  /// the level's tile grid), or nullptr when it is not resident: use a
  /// coarser level. Levels coarsest_level.. are always resident.
  virtual const TileBlock* tile(int level, int tx, int ty) const = 0;
  /// The whole of `level` as one block (x0 = y0 = 0, w x h = the level's
  /// samples), when the source holds that level resident and contiguous for
  /// as long as its tiles stay valid; nullptr otherwise (the default). A
  /// reader that gets one for every level reads without per-tile checks
  /// (the in-memory pyramid); the answer is the same data tile() gives.
  virtual const TileBlock* level_block(int level) const {
    (void)level;
    return nullptr;
  }
};

}  // namespace terrasprite
