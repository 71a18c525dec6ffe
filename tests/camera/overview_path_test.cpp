// SPDX-License-Identifier: MIT
// The overview flight (render's default): the paper flight on terrains as
// steep as the synthetic one, brought closer over flat ones.
#include <gtest/gtest.h>

#include <cmath>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/terrain/synth.h"

using namespace terrasprite;

namespace {

// n x n samples `spacing` apart: a cone `relief` metres high at the centre.
Heightfield cone(int n, double spacing, double relief) {
  Heightfield h;
  h.width = h.height = n;
  h.spacing_x = h.spacing_y = spacing;
  h.heights.resize(std::size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double r = std::hypot(i - (n - 1) / 2.0, j - (n - 1) / 2.0) / ((n - 1) / 2.0);
      h.at(i, j) = float(relief * std::max(0.0, 1 - r));
    }
  return h;
}

}  // namespace

TEST(OverviewPath, IsThePaperPathOnTheSyntheticTerrain) {  // about 0.3 s: 129^2 synthesis
  SynthOptions s;
  s.size = 129;
  const Heightfield h = synthesize_terrain(s);
  EXPECT_DOUBLE_EQ(overview_scale(h), 1.0);
  const auto a = paper_path(h, 12, 1.0), b = overview_path(h, 12, 1.0);
  for (int f = 0; f < 12; ++f) EXPECT_EQ(a[f].position, b[f].position);
}

TEST(OverviewPath, ComesCloserOverAFlatWideTerrain) {
  const Heightfield h = cone(101, 1000, 1000);  // 100 km across, 1 km of relief
  EXPECT_DOUBLE_EQ(overview_scale(h), 0.35);
  const auto paper = paper_path(h, 46, 1.0), over = overview_path(h, 46, 1.0);
  const glm::dvec3 centre(0, 0, h.sample(0, 0));
  for (int f : {0, 10, 45})
    EXPECT_NEAR(glm::length(over[f].position - centre),
                0.35 * glm::length(paper[f].position - centre), 1e-6 * h.extent());
  // The terrain fills the first frame: straight down from under 0.5 E up.
  EXPECT_LT(over[0].position.z, 0.5 * h.extent());
}
