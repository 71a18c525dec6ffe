// SPDX-License-Identifier: MIT
// The march's vector colour pass gives the scalar reader's colours bit for
// bit: inside cells, on sample lines, and clamped past every edge.
#include "voxel/hit_colors.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "voxel/tile_reader.h"

namespace terrasprite {
namespace {

TEST(HitColors, MatchTheScalarBilinearReadBitForBit) {
  TerrainOptions o;
  o.synthetic_size = 67;
  o.erosion_passes = 0;
  const Terrain t = load_terrain(o);
  const VoxelTerrain vt(t);
  BasicTileReader<true> tiles(vt);
  std::mt19937 rng(7);
  for (int L = 0; L <= 2; ++L) {
    const auto* slot = tiles.cell(L, 0, 0);
    const LevelColors level{slot->color, slot->off, slot->stride, tiles.width(L), tiles.height(L)};
    const double scale = 1.0 / double(1 << L);
    // A line across the grid and past its edges (level-0 grid units per metre).
    const HitLine line{-9.5, 70.25, 0.37, -0.41, scale};
    std::uniform_real_distribution<double> dist(-20.0, 250.0);
    std::vector<double> ts(103);  // not a multiple of 4: a tail is left to the caller
    for (double& v : ts) v = dist(rng);
    ts[0] = 0.0;
    ts[1] = 25.0;  // whole level-0 coordinates (a sample line)
    std::vector<MarchHit> hits(ts.size(), MarchHit{0.f, 0u});
    const std::size_t done = hit_colors(level, line, ts.data(), hits.data(), hits.size());
    EXPECT_EQ(done % 4, 0u);
    EXPECT_LE(done, hits.size());
    for (std::size_t k = 0; k < done; ++k) {
      const double i = (line.u0 + ts[k] * line.du) * scale, j = (line.v0 + ts[k] * line.dv) * scale;
      ASSERT_EQ(hits[k].color, tiles.bilinear_color(L, i, j)) << "level " << L << " hit " << k;
    }
  }
}

}  // namespace
}  // namespace terrasprite
