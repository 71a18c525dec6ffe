// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/terrain/synth.h"

using namespace terrasprite;

TEST(Synthetic, DeterministicSeededWithExpectedRelief) {
  SynthOptions o;
  o.size = 129;
  Heightfield a = synthesize_terrain(o), b = synthesize_terrain(o);
  EXPECT_EQ(a.heights, b.heights);
  EXPECT_NEAR(a.max_height() - a.min_height(), 2000.0, 200.0);
  o.seed = 2;
  Heightfield c = synthesize_terrain(o);
  EXPECT_NE(a.heights, c.heights);
}

TEST(Synthetic, HasRidgesAndValleysNotNoise) {
  SynthOptions o;
  o.size = 257;
  Heightfield h = synthesize_terrain(o);
  // Neighbouring samples are close compared with the relief: smooth mountains.
  double max_step = 0;
  for (int j = 0; j < h.height; ++j)
    for (int i = 1; i < h.width; ++i)
      max_step = std::max(max_step, double(std::abs(h.at(i, j) - h.at(i - 1, j))));
  EXPECT_LT(max_step, 0.15 * (h.max_height() - h.min_height()));
  EXPECT_GT(max_step, 5.0);
}

TEST(Synthetic, TinyAndInvalidSizes) {
  SynthOptions o;
  o.size = 2;
  EXPECT_EQ(synthesize_terrain(o).heights.size(), 4u);
  o.size = 1;
  EXPECT_THROW(synthesize_terrain(o), InputError);
}

TEST(Terrain, DefaultIsSyntheticWithDerivedTexture) {
  TerrainOptions o;
  o.synthetic_size = 65;
  Terrain t = load_terrain(o);
  EXPECT_EQ(t.heights.width, 65);
  EXPECT_EQ(t.texture_name, "derived");
  EXPECT_EQ(t.texture.width, 128);
  o.exaggeration = 2;
  Terrain t2 = load_terrain(o);
  EXPECT_NEAR(t2.heights.max_height(), 2 * t.heights.max_height(), 1e-3);
  o.texture = "checker";
  EXPECT_EQ(load_terrain(o).texture_name, "checker");
}
