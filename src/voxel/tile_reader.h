// SPDX-License-Identifier: MIT
// Reading a TerrainTiles source sample by sample: one cached tile per level,
// so a march asks the source only when it crosses a tile edge, and bilinear
// reads that fall back to a coarser level where a tile is not resident.
#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>

#include "terrasprite/terrain_tiles.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {

/// Per-thread, per-march cursor over a TerrainTiles (levels 0..31). Cheap to
/// construct; not shared between threads.
class TileReader {
 public:
  static constexpr int kMaxLevels = 32;

  explicit TileReader(const TerrainTiles& src) : src_(src), g_(src.grid()) {
    nlev_ = std::min(g_.bound_levels, kMaxLevels);
    for (int L = 0; L < nlev_; ++L) {
      w_[L] = g_.level_width(L);
      h_[L] = g_.level_height(L);
    }
  }
  const TerrainGrid& grid() const { return g_; }
  int width(int level) const { return w_[level]; }    ///< samples of `level` (>= 2)
  int height(int level) const { return h_[level]; }

  /// The resident tile holding cell (a, b) of `level` (0 <= a < width - 1,
  /// 0 <= b < height - 1), or null.
  const TileBlock* cell(int level, int a, int b) {
    const Slot& s = slots_[level];
    if (unsigned(a - s.x0) < s.cw && unsigned(b - s.y0) < s.ch) return s.block;
    return refill(level, a, b);
  }

  static float height_at(const TileBlock& t, int i, int j) {
    return t.height[std::ptrdiff_t(j - t.y0) * t.stride + (i - t.x0)];
  }
  static std::uint32_t color_at(const TileBlock& t, int i, int j) {
    return t.color[std::ptrdiff_t(j - t.y0) * t.stride + (i - t.x0)];
  }
  /// Bound of cell (a, b) of `level`; +inf where the tile is not resident.
  float bound(int level, int a, int b) {
    const TileBlock* t = cell(level, a, b);
    if (!t) return std::numeric_limits<float>::infinity();
    return t->bound[std::ptrdiff_t(b - t->y0) * t->bound_stride + (a - t->x0)];
  }

  /// Bilinear height of `level` at fractional level coordinates (i, j),
  /// clamped; from a coarser level where the tile is missing.
  float bilinear_height(int level, double i, double j) {
    int i0, j0;
    float fi, fj;
    cell_of(level, i, j, i0, j0);
    const TileBlock* t = cell(level, i0, j0);
    if (!t || !t->height) return bilinear_height(level + 1, i * 0.5, j * 0.5);
    fi = float(i - i0);
    fj = float(j - j0);
    const float* r0 = t->height + std::ptrdiff_t(j0 - t->y0) * t->stride + (i0 - t->x0);
    const float* r1 = r0 + t->stride;
    float a = r0[0] + (r0[1] - r0[0]) * fi;
    float b = r1[0] + (r1[1] - r1[0]) * fi;
    return a + (b - a) * fj;
  }

  /// Bilinear packed colour (8-bit weights) of `level` at (i, j), clamped.
  std::uint32_t bilinear_color(int level, double i, double j) {
    int i0, j0;
    cell_of(level, i, j, i0, j0);
    const TileBlock* t = cell(level, i0, j0);
    if (!t || !t->color) return bilinear_color(level + 1, i * 0.5, j * 0.5);
    const std::uint32_t fi = std::uint32_t((i - i0) * 256.0 + 0.5),
                        fj = std::uint32_t((j - j0) * 256.0 + 0.5);
    const std::uint32_t* r0 = t->color + std::ptrdiff_t(j0 - t->y0) * t->stride + (i0 - t->x0);
    const std::uint32_t* r1 = r0 + t->stride;
    return lerp_packed(lerp_packed(r0[0], r0[1], fi), lerp_packed(r1[0], r1[1], fi), fj);
  }

 private:
  struct Slot {
    const TileBlock* block = nullptr;
    int x0 = 0, y0 = 0;
    unsigned cw = 0, ch = 0;  // cells covered; 0 = empty slot
  };

  // Clamps (i, j) into the level and picks the cell whose corners surround it.
  void cell_of(int level, double& i, double& j, int& i0, int& j0) const {
    i = std::clamp(i, 0.0, double(w_[level] - 1));
    j = std::clamp(j, 0.0, double(h_[level] - 1));
    i0 = std::min(int(i), w_[level] - 2);
    j0 = std::min(int(j), h_[level] - 2);
  }

  const TileBlock* refill(int level, int a, int b) {
    const int lg = g_.tile_log2;
    const TileBlock* t = src_.tile(level, a >> lg, b >> lg);
    Slot& s = slots_[level];
    if (!t) {
      s = Slot{};
      return nullptr;
    }
    s = Slot{t, t->x0, t->y0, unsigned(t->w - 1), unsigned(t->h - 1)};
    return t;
  }

  const TerrainTiles& src_;
  const TerrainGrid& g_;
  int nlev_ = 0;
  int w_[kMaxLevels] = {}, h_[kMaxLevels] = {};
  Slot slots_[kMaxLevels];
};

}  // namespace terrasprite
