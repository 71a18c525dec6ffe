// SPDX-License-Identifier: MIT
// The tile accessor the ray caster reads terrain through: the in-memory
// pyramid's tiles agree with the height field and bound it, and the caster
// falls back to coarser levels where tiles are not resident.
#include "terrasprite/voxel/terrain_tiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

#include "terrasprite/quality/quality.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite {
namespace {

Terrain small_terrain(int n) {
  TerrainOptions o;
  o.synthetic_size = n;
  o.erosion_passes = 0;
  return load_terrain(o);
}

TEST(TerrainTiles, InMemoryTilesViewTheHeightFieldAndBoundIt) {
  const Terrain t = small_terrain(300);  // level 0: 3 x 3 tiles of 128 cells, the last narrow
  const VoxelTerrain vt(t);
  const TerrainGrid& g = vt.grid();
  ASSERT_EQ(g.width, 300);
  ASSERT_EQ(g.coarsest_level, vt.levels() - 1);
  ASSERT_GT(g.bound_levels, g.coarsest_level);
  const int T = 1 << g.tile_log2;
  for (int L = 0; L < g.bound_levels; ++L) {
    const int cw = g.level_width(L) - 1, ch = g.level_height(L) - 1;
    for (int ty = 0; ty * T < ch; ++ty)
      for (int tx = 0; tx * T < cw; ++tx) {
        const TileBlock* b = vt.tile(L, tx, ty);
        ASSERT_NE(b, nullptr) << "level " << L << " tile " << tx << "," << ty;
        EXPECT_EQ(b->x0, tx * T);
        EXPECT_EQ(b->w, std::min(T, cw - tx * T) + 1);
        EXPECT_EQ(b->height == nullptr, L > g.coarsest_level);
        // Every level-0 height in a cell is under that cell's bound.
        for (int b_ = 0; b_ < b->h - 1; ++b_)
          for (int a = 0; a < b->w - 1; ++a) {
            const float bound = b->bound[b_ * b->bound_stride + a];
            EXPECT_LE(bound, b->max_height);
            const int s = 1 << L, x = (b->x0 + a) * s, y = (b->y0 + b_) * s;
            for (int yy = y; yy <= std::min(y + s, g.height - 1); yy += std::max(1, s / 2))
              for (int xx = x; xx <= std::min(x + s, g.width - 1); xx += std::max(1, s / 2))
                ASSERT_LE(t.heights.at(xx, yy), bound) << "level " << L;
          }
        if (L == 0) {
          for (int j = 0; j < b->h; ++j)
            for (int i = 0; i < b->w; ++i)
              ASSERT_EQ(b->height[j * b->stride + i], t.heights.at(b->x0 + i, b->y0 + j));
        }
      }
    EXPECT_EQ(vt.tile(L, (cw + T - 1) / T, 0), nullptr) << "past the level's tiles";
    // The whole level as one block views the same samples and bounds as its tiles.
    const TileBlock* all = vt.level_block(L);
    ASSERT_NE(all, nullptr) << "level " << L;
    EXPECT_EQ(all->x0, 0);
    EXPECT_EQ(all->w, cw + 1);
    EXPECT_EQ(all->h, ch + 1);
    float tiles_max = -std::numeric_limits<float>::infinity();
    for (int ty = 0; ty * T < ch; ++ty)
      for (int tx = 0; tx * T < cw; ++tx) {
        const TileBlock* b = vt.tile(L, tx, ty);
        tiles_max = std::max(tiles_max, b->max_height);
        ASSERT_EQ(b->bound, all->bound + std::ptrdiff_t(b->y0) * all->bound_stride + b->x0);
        if (b->height) {
          ASSERT_EQ(b->height, all->height + std::ptrdiff_t(b->y0) * all->stride + b->x0);
        }
      }
    EXPECT_EQ(all->max_height, tiles_max);
  }
  EXPECT_EQ(vt.level_block(-1), nullptr);
  EXPECT_EQ(vt.level_block(g.bound_levels), nullptr);
  EXPECT_EQ(vt.tile(-1, 0, 0), nullptr) << "no finer level in memory";
  EXPECT_EQ(vt.tile(g.bound_levels, 0, 0), nullptr);
}

// A source that forwards to the in-memory pyramid but hides some tiles of
// the finest levels, as a streaming cache would before they arrive.
class PartlyResident : public TerrainTiles {
 public:
  PartlyResident(const VoxelTerrain& base, int hide_below, bool checker)
      : base_(base), hide_below_(hide_below), checker_(checker) {}
  const TerrainGrid& grid() const override { return base_.grid(); }
  const TileBlock* tile(int level, int tx, int ty) const override {
    if (level < hide_below_ && (!checker_ || (tx + ty) % 2 == 0)) return nullptr;
    return base_.tile(level, tx, ty);
  }

 private:
  const VoxelTerrain& base_;
  int hide_below_;
  bool checker_;
};

Frame render_with(const TerrainTiles& src, VoxelVariant v, const Camera& c, int w, int h) {
  VoxelOptions o;
  o.variant = v;
  o.threads = 2;
  VoxelRenderer r(src, w, h, o);
  return r.render(c);
}

TEST(TerrainTiles, MissingTilesFallBackToCoarserLevels) {
  const Terrain t = small_terrain(513);
  const VoxelTerrain vt(t);
  const int W = 160, H = 90;
  Camera c;
  c.position = {0, -0.55 * t.heights.extent(), t.heights.max_height() + 400.0};
  c.pitch_deg = -25;
  c.aspect = double(W) / H;
  for (VoxelVariant v : {VoxelVariant::kCoherent, VoxelVariant::kMultires}) {
    const Frame full = render_with(vt, v, c, W, H);
    // Everything resident through tile() alone (no level_block, so the
    // tiled reader, where vt takes the whole-level one): the very same image.
    const Frame same = render_with(PartlyResident(vt, 0, false), v, c, W, H);
    EXPECT_EQ(full.color.rgba, same.color.rgba);
    // Half the level-0 tiles missing, or all of levels 0 and 1: the image
    // degrades gracefully (coarser terrain), no holes of sky.
    for (auto [hide, checker] : {std::tuple{1, true}, std::tuple{2, false}}) {
      const Frame coarse = render_with(PartlyResident(vt, hide, checker), v, c, W, H);
      int sky_full = 0, sky_coarse = 0;
      for (std::size_t i = 0; i < full.depth.size(); ++i) {
        sky_full += std::isinf(full.depth[i]);
        sky_coarse += std::isinf(coarse.depth[i]);
      }
      EXPECT_NEAR(sky_coarse, sky_full, 0.02 * W * H) << to_string(v) << " hide " << hide;
      const double s = quality::ssim(full.color.view(), coarse.color.view()).ssim;
      EXPECT_GT(s, 0.5) << to_string(v) << " hide " << hide;
      EXPECT_LT(s, 1.0) << "the coarser levels were not read";
    }
  }
}

}  // namespace
}  // namespace terrasprite
