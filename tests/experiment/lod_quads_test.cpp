// SPDX-License-Identifier: MIT
// The default coarse grid of the lod and sprite modes, from the terrain.
#include <gtest/gtest.h>

#include "terrasprite/experiment/render_stack.h"

using namespace terrasprite;

namespace {

Heightfield grid(int n, double spacing) {
  Heightfield h;
  h.width = h.height = n;
  h.spacing_x = h.spacing_y = spacing;
  h.heights.assign(std::size_t(n) * n, 0.f);
  return h;
}

}  // namespace

TEST(AutoLodQuads, PaperSetupKeeps16AndLargeDemsGetKilometreQuads) {
  EXPECT_EQ(auto_lod_quads(grid(513, 30)), 16);     // the synthetic terrain: the paper's grid
  EXPECT_EQ(auto_lod_quads(grid(65, 30)), 16);      // small: never coarser than 16
  EXPECT_EQ(auto_lod_quads(grid(1025, 30)), 32);    // 32 samples a quad
  EXPECT_EQ(auto_lod_quads(grid(1201, 92)), 110);   // an SRTM tile: about 1 km a quad
  EXPECT_EQ(auto_lod_quads(grid(1025, 160)), 128);  // at most one quad per 8 samples
  EXPECT_EQ(auto_lod_quads(grid(9, 30)), 8);        // never more quads than the terrain has
}
