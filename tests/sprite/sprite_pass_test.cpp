// SPDX-License-Identifier: MIT
// The sprite pass's draw order: coarse cells nearest to the eye first.
#include "sprite/sprite_pass.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "sprite_test_util.h"

namespace terrasprite {
namespace {

// A 4 x 4 grid (rows run south) seen from past its NW corner: the NW cell
// first, the SE cell last, and every cell after the cells nearer than it.
// CI cost: under 0.01 s.
TEST(SpritePass, CellsAreDrawnNearestFirst) {
  const CoarseGrid g = make_coarse_grid(sprite_test::flat(65, 10.0), 4);
  const glm::dvec3 nw = g.vertex(0, 0) + glm::dvec3(-100, 100, 500);
  std::vector<int> order;
  front_to_back_cells(g, nw, order);
  ASSERT_EQ(order.size(), 16u);
  EXPECT_EQ(order.front(), 0);
  EXPECT_EQ(order.back(), 15);
  auto d2 = [&](int q) {
    const glm::dvec2 d = glm::dvec2(g.centre[q]) - glm::dvec2(nw);
    return glm::dot(d, d);
  };
  for (std::size_t i = 1; i < order.size(); ++i) EXPECT_LE(d2(order[i - 1]), d2(order[i]));
  // From above the middle the four middle cells come first.
  front_to_back_cells(g, glm::dvec3(0, 0, 500), order);
  std::vector<int> first(order.begin(), order.begin() + 4);
  std::sort(first.begin(), first.end());
  EXPECT_EQ(first, (std::vector<int>{5, 6, 9, 10}));
}

}  // namespace
}  // namespace terrasprite
