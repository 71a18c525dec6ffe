// SPDX-License-Identifier: MIT
// High-resolution insets at their own resolution (Cohen-Or et al.'s target
// areas): sparse levels finer than the base's level 0, over a window of the
// fine grid around the insets, written as a tile set of their own beside the
// base's (DIR/fine) and streamed with it (see FineLevelsInfo).
#pragma once
#include <string>
#include <vector>

#include "terrasprite/stream/insets.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite {

/// The fine window: the base bilinearly upsampled by 2^levels, the insets
/// composited into it in order with their border blend counted in fine
/// samples, and a colour texture (the base's, upsampled, shaded by the
/// insets' detail).
struct FineWindow {
  int levels = 0;  ///< K: spacing = the base's / 2^K
  /// Sample (0, 0) in the fine grid; it and the window's cells are multiples
  /// of T 2^(K-1) (whole tiles at every fine level), or it ends at the grid's edge.
  int origin_x = 0, origin_y = 0;
  Terrain terrain;            ///< the window's heights and texture
  std::vector<float> weight;  ///< per sample, the highest inset weight (0: the base's)
  std::vector<InsetResult> results;
};

/// Builds the window over the union of `insets` (warped into `grid.wkt`) on
/// `base` (whose samples lie on `grid`), for tiles of 2^tile_log2 cells.
/// levels 1..8. Throws InputError naming an inset that covers no sample, or
/// when the window would exceed 2^30 samples.
FineWindow build_fine_window(const Terrain& base, const GridGeo& grid,
                             const std::vector<InsetSpec>& insets, int levels, int tile_log2);

/// The tiles of the window's levels 0..K-1 that hold inset data, and the
/// highest window sample in each base level-0 cell (for FineLevelsInfo).
FineLevelsInfo fine_levels_info(const FineWindow& window, int base_w, int base_h, int tile_log2);

/// build_fine_window, then its pyramid written as a tile set into `dir`/fine
/// (with `options`' encoding), and the FineLevelsInfo for the base's tiles.json.
FineLevelsInfo write_fine_insets(const Terrain& base, const GridGeo& grid,
                                 const std::vector<InsetSpec>& insets, int levels,
                                 const TileWriteOptions& options, const std::string& dir);

}  // namespace terrasprite
