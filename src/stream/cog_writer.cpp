// SPDX-License-Identifier: MIT
// Writes the ray caster's pyramid as Cloud-Optimized GeoTIFFs. GDAL's COG
// driver is CreateCopy-only and builds area-aligned overviews of its own; we
// hand it a VRT whose bands view the pyramid in memory (MEM datasets over our
// buffers) and whose <Overview> elements are our vertex-aligned levels, and
// ask it to keep them (OVERVIEWS=FORCE_USE_EXISTING): the file's overview k
// is level k + 1 exactly, whatever its size.
#include <fmt/format.h>
#include <gdal_priv.h>

#include <limits>
#include <string>
#include <vector>

#include "stream/cog_vrt.h"
#include "stream/tile_set_json.h"
#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/stream/tiled_terrain.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {
namespace {

// `d`'s max pyramid raised by `cell_max` (per level-0 cell, the highest
// sample of a finer surface inside it): each level takes the max over its
// cells, dilated by one cell as the pyramid's own bounds are.
std::vector<MaxLevel> raise_bounds(const VoxelTerrain::Data& d,
                                   const std::vector<float>& cell_max) {
  std::vector<MaxLevel> out = d.maxes;
  if (out.empty() || cell_max.size() != std::size_t(out[0].w) * std::size_t(out[0].h))
    throw InputError("fine levels: the base cell maxima do not match the terrain");
  std::vector<float> raw = cell_max;  // undilated, cells of the current level
  int rw = out[0].w, rh = out[0].h;
  for (std::size_t k = 0; k < out.size(); ++k) {
    MaxLevel& m = out[k];
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

void write_tiled_terrain(const VoxelTerrain& terrain, const std::optional<GeoTransform>& geo,
                         const std::string& dir, const TileWriteOptions& o) {
  check_write_options(o);
  detail::ensure_gdal();
  const VoxelTerrain::Data& d = terrain.data();
  if (!d.has_area()) throw InputError(fmt::format("{}: the terrain has no area to tile", dir));

  std::vector<LevelSource> heights, colors, bounds;
  for (const PyramidLevel& l : d.levels) {
    heights.push_back({mem_source(l.height.data(), l.w, l.h, "Float32", 1, 4), l.w, l.h});
    colors.push_back({mem_source(l.color.data(), l.w, l.h, "Byte", 4, 4), l.w, l.h});
  }
  // Fine levels: the base's bounds raised to cover the inset's samples.
  const std::vector<MaxLevel> raised =
      o.fine ? raise_bounds(d, o.fine->base_cell_max) : std::vector<MaxLevel>{};
  const std::vector<MaxLevel>& maxes = o.fine ? raised : d.maxes;
  std::vector<const float*> bound_data;
  for (const MaxLevel& m : maxes) {
    bounds.push_back({mem_source(m.bound.data(), m.w, m.h, "Float32", 1, 4), m.w, m.h});
    bound_data.push_back(m.bound.data());
  }
  write_level_cogs(heights, colors, bounds, geo, dir, o);
  write_tile_set_json(terrain.grid(), tile_maxima(terrain.grid(), bound_data, o.tile_log2), geo, o,
                      dir + "/tiles.json");
}

}  // namespace terrasprite
