// SPDX-License-Identifier: MIT
// The combined grid of a base terrain and its sparse finer levels (insets at
// their own resolution): the base's levels shifted up by K, levels 0..K-1
// present only inside the fine window.
#include <algorithm>

#include "stream/tile_file.h"
#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite {

TerrainGrid combined_grid(const TileSetInfo& set) {
  if (!set.fine || !set.fine_set) return set.grid;
  const int k = set.fine->levels;
  const TerrainGrid& b = set.grid;
  const TerrainGrid& f = set.fine_set->grid;
  TerrainGrid g = b;
  g.width = TerrainGrid::level_size(b.width, -k);
  g.height = TerrainGrid::level_size(b.height, -k);
  g.spacing_x = b.spacing_x / double(1 << k);
  g.spacing_y = b.spacing_y / double(1 << k);
  g.min_height = std::min(b.min_height, f.min_height);
  g.max_height = std::max(b.max_height, f.max_height);
  g.coarsest_level = b.coarsest_level + k;
  g.bound_levels = b.bound_levels + k;
  g.sparse_levels = k;
  g.sparse_x0 = set.fine->origin_x;
  g.sparse_y0 = set.fine->origin_y;
  g.sparse_x1 = std::min(g.width - 1, set.fine->origin_x + f.width - 1);
  g.sparse_y1 = std::min(g.height - 1, set.fine->origin_y + f.height - 1);
  return g;
}

void fine_world_shift(const TileSetInfo& base, double& x, double& y) {
  x = y = 0;
  if (!base.fine || !base.fine_set) return;
  const double s = double(1 << base.fine->levels);
  const TerrainGrid& b = base.grid;
  const TerrainGrid& f = base.fine_set->grid;
  // Window sample i sits at base index (origin + i) / 2^K; its own frame
  // centres the window on the world origin.
  x = ((base.fine->origin_x + (f.width - 1) * 0.5) / s - (b.width - 1) * 0.5) * b.spacing_x;
  y = ((b.height - 1) * 0.5 - (base.fine->origin_y + (f.height - 1) * 0.5) / s) * b.spacing_y;
}

bool fine_window_tile(const TileSetInfo& f, int level, int& tx, int& ty) {
  if (level < 0 || level >= int(f.tiles_x.size())) return false;
  tx -= (f.origin_x >> level) >> f.grid.tile_log2;
  ty -= (f.origin_y >> level) >> f.grid.tile_log2;
  return tx >= 0 && ty >= 0 && tx < f.tiles_x[std::size_t(level)] &&
         ty < f.tiles_y[std::size_t(level)] && f.tile_present(level, tx, ty);
}

}  // namespace terrasprite
