// SPDX-License-Identifier: MIT
// The prefetch footprint: the tiles ahead of the eye and under it, not those
// behind; the motion pushes it forwards.
#include "stream/footprint.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace terrasprite {
namespace {

// A 257 x 257 grid at 30 m in 16-cell tiles (16 x 16 at level 0), no files needed.
TileSetInfo grid_only() {
  TileSetInfo s;
  s.grid.width = s.grid.height = 257;
  s.grid.spacing_x = s.grid.spacing_y = 30;
  s.grid.tile_log2 = 4;
  s.grid.coarsest_level = s.grid.bound_levels = 1;
  for (int L = 0; L < 1; ++L) {
    s.tiles_x.push_back(16);
    s.tiles_y.push_back(16);
    s.tile_max.emplace_back(256, 100.f);
  }
  return s;
}

bool has(const std::vector<TileKey>& keys, int tx, int ty) {
  return std::any_of(keys.begin(), keys.end(),
                     [&](const TileKey& k) { return k.tx == tx && k.ty == ty; });
}

TEST(Footprint, AheadAndUnderTheEyeNotBehind) {
  const TileSetInfo s = grid_only();
  Camera c;  // at the centre (tile 8, 8 holds sample 128), looking north, level flight
  c.position = {0, 0, 300};
  c.yaw_deg = 0;
  c.pitch_deg = -10;
  c.aspect = 16.0 / 9;
  FootprintOptions o;
  o.levels = 1;
  o.image_height = 1080;
  std::vector<TileKey> keys;
  footprint(s, c, {0, 0, 0}, o, keys);
  EXPECT_TRUE(has(keys, 8, 8));    // under the eye
  EXPECT_TRUE(has(keys, 8, 2));    // ahead (north: smaller rows)
  EXPECT_FALSE(has(keys, 8, 14));  // behind
  for (const TileKey& k : keys) EXPECT_TRUE(k.tx >= 0 && k.tx < 16 && k.ty >= 0 && k.ty < 16);

  // Flying south fast while looking north: the look-ahead position adds tiles behind.
  std::vector<TileKey> moving;
  footprint(s, c, {0, -100, 0}, o, moving);
  EXPECT_TRUE(has(moving, 8, 14));
}

}  // namespace
}  // namespace terrasprite
