// SPDX-License-Identifier: MIT
// A tiled terrain read whole into memory: the in-memory source a streamed
// flythrough is compared with (same files, same samples, every tile resident).
#include <fmt/format.h>

#include "stream/tile_file.h"
#include "terrasprite/common/error.h"
#include "terrasprite/stream/streaming_tiles.h"

namespace terrasprite {

struct ResidentTiles::Impl {
  TileSetInfo set;
  TerrainGrid cgrid;                          // the renderer's grid (fine levels first)
  int k = 0;                                  // fine levels (insets), from `fine`
  std::unique_ptr<ResidentTiles> fine;        // the fine window set, wholly in memory
  std::vector<TileData> levels;               // one whole-level block each
  std::vector<std::vector<TileBlock>> tiles;  // per level, row-major tiles viewing it
};

ResidentTiles::ResidentTiles(const TileSetInfo& set) : p_(std::make_unique<Impl>()) {
  p_->set = set;
  p_->cgrid = combined_grid(set);
  if (set.fine && set.fine_set) {
    p_->k = set.fine->levels;
    p_->fine = std::make_unique<ResidentTiles>(*set.fine_set);
  }
  TileFile file(p_->set);
  const TerrainGrid& g = p_->set.grid;
  p_->levels.resize(std::size_t(g.bound_levels));
  for (int L = 0; L < g.bound_levels; ++L) {
    TileData& d = p_->levels[std::size_t(L)];
    std::string error;
    if (!file.read_level(L, d, error)) throw InputError(fmt::format("{}: {}", set.dir, error));
    auto& tl = p_->tiles.emplace_back();
    const int nx = p_->set.tiles_x[std::size_t(L)], ny = p_->set.tiles_y[std::size_t(L)];
    for (int ty = 0; ty < ny; ++ty)
      for (int tx = 0; tx < nx; ++tx) {
        TileBlock b = d.block;
        tile_window(p_->set, L, tx, ty, b.x0, b.y0, b.w, b.h);
        const std::size_t at = std::size_t(b.y0) * d.block.stride + b.x0;
        if (b.height) b.height += at;
        if (b.color) b.color += at;
        b.bound += std::size_t(b.y0) * d.block.bound_stride + b.x0;
        b.x0 += set.origin_x >> L;  // a fine window set: the enclosing grid's indices
        b.y0 += set.origin_y >> L;
        b.max_height = p_->set.tile_max[std::size_t(L)][std::size_t(ty) * nx + tx];
        tl.push_back(b);
      }
  }
}

ResidentTiles::~ResidentTiles() = default;

const TerrainGrid& ResidentTiles::grid() const {
  return p_->cgrid;
}

const TileBlock* ResidentTiles::tile(int level, int tx, int ty) const {
  if (p_->k) {
    if (level < p_->k)
      return fine_window_tile(*p_->set.fine_set, level, tx, ty) ? p_->fine->tile(level, tx, ty)
                                                                : nullptr;
    level -= p_->k;
  }
  if (level < 0 || level >= int(p_->tiles.size())) return nullptr;
  const int nx = p_->set.tiles_x[std::size_t(level)], ny = p_->set.tiles_y[std::size_t(level)];
  if (tx < 0 || ty < 0 || tx >= nx || ty >= ny) return nullptr;
  return &p_->tiles[std::size_t(level)][std::size_t(ty) * nx + tx];
}

const TileBlock* ResidentTiles::level_block(int level) const {
  if (p_->k) return nullptr;  // sparse fine levels: read tile by tile
  if (level < 0 || level >= int(p_->levels.size())) return nullptr;
  return &p_->levels[std::size_t(level)].block;
}

}  // namespace terrasprite
