// SPDX-License-Identifier: MIT
// Reading a TerrainTiles source sample by sample: one cached tile per level,
// so a march asks the source only when it crosses a tile edge, and bilinear
// reads that fall back to a coarser level where a tile is not resident.
#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>

#include "terrasprite/voxel/terrain_tiles.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {

/// Per-thread, per-march cursor over a TerrainTiles (levels 0..31). Cheap to
/// construct; not shared between threads.
///
/// kWholeLevels: every level comes from `level_block()` (the caller checked
/// `has_whole_levels`), so a read never checks or changes tiles. The march is
/// instantiated for both so an in-memory pyramid pays nothing for the tiles.
template <bool kWholeLevels>
class BasicTileReader {
 public:
  static constexpr int kMaxLevels = 32;

  explicit BasicTileReader(const TerrainTiles& src) : src_(src), g_(src.grid()) {
    nlev_ = std::min(g_.bound_levels, kMaxLevels);
    for (int L = 0; L < nlev_; ++L) {
      w_[L] = g_.level_width(L);
      h_[L] = g_.level_height(L);
      if constexpr (kWholeLevels) load(slots_[L], src.level_block(L));
    }
  }
  /// Whether `src` hands out every level 0..min(bound_levels, 32)-1 whole.
  static bool has_whole_levels(const TerrainTiles& src) {
    const int n = std::min(src.grid().bound_levels, kMaxLevels);
    for (int L = 0; L < n; ++L)
      if (!src.level_block(L)) return false;
    return true;
  }
  const TerrainGrid& grid() const { return g_; }
  int width(int level) const { return w_[level]; }  ///< samples of `level` (>= 2)
  int height(int level) const { return h_[level]; }

  /// A resident tile's views, offset so level indices address them directly.
  struct alignas(64) Slot {  // hot fields first, one cache line
    int x0 = 0, y0 = 0;
    unsigned cw = 0, ch = 0;  // cells covered; 0 = empty slot
    const float* height = nullptr;
    std::ptrdiff_t off = 0, stride = 0;  // off = -(y0 stride + x0)
    const std::uint32_t* color = nullptr;
    const float* bound = nullptr;
    std::ptrdiff_t bound_off = 0, bound_stride = 0;

    float height_at(int i, int j) const { return height[off + j * stride + i]; }
    std::uint32_t color_at(int i, int j) const { return color[off + j * stride + i]; }
    float bound_at(int a, int b) const { return bound[bound_off + b * bound_stride + a]; }
  };

  /// The resident tile holding cell (a, b) of `level` (0 <= a < width - 1,
  /// 0 <= b < height - 1), or null.
  const Slot* cell(int level, int a, int b) {
    const Slot& s = slots_[level];
    if constexpr (kWholeLevels) return &s;
    if (unsigned(a - s.x0) < s.cw && unsigned(b - s.y0) < s.ch) [[likely]]
      return &s;
    return refill(level, a, b);
  }

  /// Bound of cell (a, b) of `level`; where the tile is not resident, the
  /// bound of the coarser cell holding it (looser, still a bound), or +inf
  /// past the last level.
  float bound(int level, int a, int b) {
    const Slot* t = cell(level, a, b);
    if (!t) [[unlikely]]
      return coarser_bound(level + 1, a >> 1, b >> 1);
    return t->bound_at(a, b);
  }

  /// Bilinear height of `level` (<= coarsest_level) at fractional level
  /// coordinates (i, j), clamped; from a coarser level where the tile is missing.
  float bilinear_height(int level, double i, double j) {
    int i0, j0;
    cell_of(level, i, j, i0, j0);
    const Slot* t = cell(level, i0, j0);
    if (!t) [[unlikely]]  // levels <= coarsest_level carry samples where resident
      return coarser_height(level + 1, i * 0.5, j * 0.5);
    const float fi = float(i - i0), fj = float(j - j0);
    const float* r0 = t->height + t->off + j0 * t->stride + i0;
    const float* r1 = r0 + t->stride;
    float a = r0[0] + (r0[1] - r0[0]) * fi;
    float b = r1[0] + (r1[1] - r1[0]) * fi;
    return a + (b - a) * fj;
  }

  /// Bilinear packed colour (8-bit weights) of `level` at (i, j), clamped.
  std::uint32_t bilinear_color(int level, double i, double j) {
    int i0, j0;
    cell_of(level, i, j, i0, j0);
    const Slot* t = cell(level, i0, j0);
    if (!t) [[unlikely]]
      return coarser_color(level + 1, i * 0.5, j * 0.5);
    const std::uint32_t fi = std::uint32_t((i - i0) * 256.0 + 0.5),
                        fj = std::uint32_t((j - j0) * 256.0 + 0.5);
    const std::uint32_t* r0 = t->color + t->off + j0 * t->stride + i0;
    const std::uint32_t* r1 = r0 + t->stride;
    return lerp_packed(lerp_packed(r0[0], r0[1], fi), lerp_packed(r1[0], r1[1], fi), fj);
  }

  // The fallbacks, out of line so the resident path stays small and inlined.
  [[gnu::noinline]] float coarser_bound(int level, int a, int b) {
    if (level >= nlev_) return std::numeric_limits<float>::infinity();
    return bound(level, a, b);
  }
  [[gnu::noinline]] float coarser_height(int level, double i, double j) {
    return bilinear_height(level, i, j);
  }
  [[gnu::noinline]] std::uint32_t coarser_color(int level, double i, double j) {
    return bilinear_color(level, i, j);
  }

 private:
  // Clamps (i, j) into the level and picks the cell whose corners surround it.
  void cell_of(int level, double& i, double& j, int& i0, int& j0) const {
    i = std::clamp(i, 0.0, double(w_[level] - 1));
    j = std::clamp(j, 0.0, double(h_[level] - 1));
    i0 = std::min(int(i), w_[level] - 2);
    j0 = std::min(int(j), h_[level] - 2);
  }

  [[gnu::noinline]] const Slot* refill(int level, int a, int b) {
    const int lg = g_.tile_log2;
    Slot& s = slots_[level];
    return load(s, src_.tile(level, a >> lg, b >> lg));
  }

  static const Slot* load(Slot& s, const TileBlock* t) {
    s = Slot{};
    if (!t) return nullptr;
    s.x0 = t->x0;
    s.y0 = t->y0;
    s.cw = unsigned(t->w - 1);
    s.ch = unsigned(t->h - 1);
    s.height = t->height;
    s.color = t->color;
    s.bound = t->bound;
    s.stride = t->stride;
    s.bound_stride = t->bound_stride;
    s.off = -(std::ptrdiff_t(t->y0) * t->stride + t->x0);
    s.bound_off = -(std::ptrdiff_t(t->y0) * t->bound_stride + t->x0);
    return &s;
  }

  const TerrainTiles& src_;
  const TerrainGrid& g_;
  int nlev_ = 0;
  int w_[kMaxLevels] = {}, h_[kMaxLevels] = {};
  Slot slots_[kMaxLevels];
};

using TileReader = BasicTileReader<false>;

}  // namespace terrasprite
