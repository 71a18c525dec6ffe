// SPDX-License-Identifier: MIT
// Writes a level pyramid held in memory (the ray caster's) as Cloud-Optimized GeoTIFFs. GDAL's COG
// driver is CreateCopy-only and builds area-aligned overviews of its own; we
// hand it a VRT whose bands view the pyramid in memory (MEM datasets over our
// buffers) and whose <Overview> elements are our vertex-aligned levels, and
// ask it to keep them (OVERVIEWS=FORCE_USE_EXISTING): the file's overview k
// is level k + 1 exactly, whatever its size.
#include <fmt/format.h>
#include <gdal_priv.h>

#include <cassert>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "stream/cog_vrt.h"
#include "stream/tile_set_json.h"
#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite {
namespace {

// One level of max-height bounds over cells, row-major, as TileBlock::bound.
struct BoundGrid {
  int w = 0, h = 0;  // cells
  std::vector<float> bound;
};

// Level `level` of `terrain` whole; throws for a source that does not hold it.
const TileBlock& whole_level(const TerrainTiles& terrain, int level) {
  const TileBlock* b = terrain.level_block(level);
  if (!b || b->x0 != 0 || b->y0 != 0)
    throw std::invalid_argument(
        fmt::format("write_tiled_terrain: level {} of the terrain is not held whole", level));
  return *b;
}

// The bounds of `terrain` raised by `cell_max` (per level-0 cell, the highest
// sample of a finer surface inside it): each level takes the max over its
// cells, dilated by one cell as the pyramid's own bounds are.
std::vector<BoundGrid> raise_bounds(const TerrainTiles& terrain,
                                     const std::vector<float>& cell_max) {
  std::vector<BoundGrid> out;
  for (int L = 0; L < terrain.grid().bound_levels; ++L) {
    const TileBlock& b = whole_level(terrain, L);
    BoundGrid m{b.w - 1, b.h - 1, {}};
    for (int y = 0; y < m.h; ++y)
      m.bound.insert(m.bound.end(), b.bound + std::ptrdiff_t(y) * b.bound_stride,
                     b.bound + std::ptrdiff_t(y) * b.bound_stride + m.w);
    out.push_back(std::move(m));
  }
  if (out.empty() || cell_max.size() != std::size_t(out[0].w) * std::size_t(out[0].h))
    throw InputError("fine levels: the base cell maxima do not match the terrain");
  std::vector<float> raw = cell_max;  // undilated, cells of the current level
  int rw = out[0].w, rh = out[0].h;
  for (std::size_t k = 0; k < out.size(); ++k) {
    BoundGrid& m = out[k];
    if (k > 0) {  // halve: a cell of level k covers 2 x 2 cells of level k - 1
      std::vector<float> next(std::size_t(m.w) * m.h, -std::numeric_limits<float>::infinity());
      for (int b = 0; b < rh; ++b)
        for (int a = 0; a < rw; ++a) {
          float& c = next[std::size_t(std::min(b / 2, m.h - 1)) * m.w + std::min(a / 2, m.w - 1)];
          c = std::max(c, raw[std::size_t(b) * rw + a]);
        }
      raw.swap(next);
      rw = m.w;
      rh = m.h;
    }
    for (int b = 0; b < m.h; ++b)
      for (int a = 0; a < m.w; ++a) {
        float v = -std::numeric_limits<float>::infinity();
        for (int y = std::max(0, b - 1); y <= std::min(m.h - 1, b + 1); ++y)
          for (int x = std::max(0, a - 1); x <= std::min(m.w - 1, a + 1); ++x)
            v = std::max(v, raw[std::size_t(y) * rw + x]);
        float& bd = m.bound[std::size_t(b) * m.w + a];
        bd = std::max(bd, v);
      }
  }
  return out;
}

}  // namespace

void write_tiled_terrain(const TerrainTiles& terrain, const std::optional<GeoTransform>& geo,
                         const std::string& dir, const TileWriteOptions& o) {
  check_write_options(o);
  detail::ensure_gdal();
  const TerrainGrid& grid = terrain.grid();
  if (!grid.has_area()) throw InputError(fmt::format("{}: the terrain has no area to tile", dir));

  std::vector<LevelSource> heights, colors, bounds;
  for (int L = 0; L <= grid.coarsest_level; ++L) {
    const TileBlock& b = whole_level(terrain, L);
    assert(b.stride == b.w);
    heights.push_back({mem_source(b.height, b.w, b.h, "Float32", 1, 4), b.w, b.h});
    colors.push_back({mem_source(b.color, b.w, b.h, "Byte", 4, 4), b.w, b.h});
  }
  // Fine levels: the base's bounds raised to cover the inset's samples.
  const std::vector<BoundGrid> raised =
      o.fine ? raise_bounds(terrain, o.fine->base_cell_max) : std::vector<BoundGrid>{};
  std::vector<const float*> bound_data;
  for (int L = 0; L < grid.bound_levels; ++L) {
    const TileBlock& b = whole_level(terrain, L);
    const int w = b.w - 1, h = b.h - 1;  // cells
    const float* data = o.fine ? raised[std::size_t(L)].bound.data() : b.bound;
    assert(o.fine || b.bound_stride == w);
    bounds.push_back({mem_source(data, w, h, "Float32", 1, 4), w, h});
    bound_data.push_back(data);
  }
  write_level_cogs(heights, colors, bounds, geo, dir, o);
  write_tile_set_json(grid, tile_maxima(grid, bound_data, o.tile_log2), geo, o,
                      dir + "/tiles.json");
}

}  // namespace terrasprite
