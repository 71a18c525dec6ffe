// SPDX-License-Identifier: MIT
// Heightfield::sample: bilinear inside the grid, clamped to its border
// outside, and never indexing outside it, whatever the coordinates.
#include "terrasprite/terrain/heightfield.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace {
using namespace terrasprite;

// 3 x 2 samples, 10 m apart: x in [-10, 10], y in [-5, 5].
Heightfield three_by_two() {
  Heightfield h;
  h.width = 3;
  h.height = 2;
  h.spacing_x = h.spacing_y = 10;
  h.heights = {1, 2, 3, 4, 5, 6};
  return h;
}

TEST(HeightfieldSample, BilinearInsideAndClampedOutside) {
  const Heightfield h = three_by_two();
  EXPECT_FLOAT_EQ(h.sample(0, 0), 3.5f);       // the middle of samples 2 and 5
  EXPECT_FLOAT_EQ(h.sample(-10, 5), 1.0f);     // sample (0, 0), the north-west corner
  EXPECT_FLOAT_EQ(h.sample(-1e6, 5), 1.0f);    // far west: the border
  EXPECT_FLOAT_EQ(h.sample(1e6, -1e6), 6.0f);  // far south-east: the corner
}

TEST(HeightfieldSample, NonFiniteCoordinatesReadTheBorder) {
  const Heightfield h = three_by_two();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::pair<double, double>> points = {
      {nan, 0}, {0, nan}, {nan, nan}, {inf, 0}, {-inf, 0}, {0, inf}, {0, -inf}, {1e308, -1e308}};
  for (const auto& [x, y] : points) {
    const float v = h.sample(x, y);
    EXPECT_TRUE(std::isfinite(v)) << x << ", " << y;
    EXPECT_GE(v, 1.0f) << x << ", " << y;
    EXPECT_LE(v, 6.0f) << x << ", " << y;
  }
  EXPECT_FLOAT_EQ(h.sample(nan, nan), h.at(0, 0));
  EXPECT_FLOAT_EQ(h.sample(inf, -inf), h.at(2, 1));
  EXPECT_FLOAT_EQ(h.sample(-inf, inf), h.at(0, 0));
}

}  // namespace
