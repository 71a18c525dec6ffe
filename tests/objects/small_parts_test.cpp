// SPDX-License-Identifier: MIT
// Small disconnected parts left out before simplification: which go (smallest
// first, within both bounds), that a uv seam does not split a part, and that
// the Kenney forest's first level spends its triangles on the trees, not on
// its stones.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "objects/small_components.h"
#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/model.h"
#include "test_util.h"

namespace ts = terrasprite;

namespace {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

// A closed tetrahedron of edge about `size` at `at`: 4 triangles. With
// `split`, its last face gets its own copies of the corners (a uv seam).
void add_tetrahedron(Mesh& m, glm::vec3 at, float size, bool split = false) {
  const auto base = std::uint32_t(m.positions.size());
  for (glm::vec3 c :
       {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
    m.positions.push_back(at + size * c);
  for (std::uint32_t i : {0u, 2u, 1u, 0u, 1u, 3u, 0u, 3u, 2u}) m.indices.push_back(base + i);
  if (!split) {
    for (std::uint32_t i : {1u, 2u, 3u}) m.indices.push_back(base + i);
    return;
  }
  const auto copy = std::uint32_t(m.positions.size());
  for (std::uint32_t i : {1u, 2u, 3u}) m.positions.push_back(m.positions[base + i]);
  for (std::uint32_t i : {0u, 1u, 2u}) m.indices.push_back(copy + i);
}

double radius(float size) {
  return 0.5 * size * std::sqrt(3.0);
}  // the unit box's half diagonal

}  // namespace

TEST(SmallParts, SmallestFirstWithinBothBounds) {
  Mesh m;
  add_tetrahedron(m, {0, 0, 0}, 10.f, true);  // the body, seam-split: one part still
  add_tetrahedron(m, {20, 0, 0}, 0.1f);
  add_tetrahedron(m, {30, 0, 0}, 0.2f);
  add_tetrahedron(m, {40, 0, 0}, 0.4f);
  double gone = -1;
  // Radius bound between the second and third small part: two go.
  auto kept = ts::detail::without_small_parts(m.positions, m.indices, radius(0.3f), 100, gone);
  EXPECT_EQ(kept.size(), m.indices.size() - 2 * 12);
  EXPECT_NEAR(gone, radius(0.2f), 1e-6);
  std::set<float> xs;
  for (std::uint32_t v : kept) xs.insert(m.positions[v].x);
  EXPECT_EQ(xs.count(20.f) + xs.count(30.f), 0u);
  EXPECT_EQ(xs.count(40.f), 1u);
  // Triangle bound: only the smallest fits in 5 triangles.
  kept = ts::detail::without_small_parts(m.positions, m.indices, 1.0, 5, gone);
  EXPECT_EQ(kept.size(), m.indices.size() - 12);
  EXPECT_NEAR(gone, radius(0.1f), 1e-6);
  // Nothing under the bound: the same indices, nothing reported.
  kept = ts::detail::without_small_parts(m.positions, m.indices, 0.01, 100, gone);
  EXPECT_EQ(kept, m.indices);
  EXPECT_EQ(gone, 0.0);
  // The seam-split body is one part: a bound above every small part but
  // under the body leaves all of the body (both sides of the seam).
  kept = ts::detail::without_small_parts(m.positions, m.indices, 1.0, 100, gone);
  EXPECT_EQ(kept.size(), 12u);
}

TEST(SmallParts, NeverEveryPart) {
  Mesh m;
  for (int i = 0; i < 4; ++i) add_tetrahedron(m, {float(i), 0, 0}, 0.1f);
  double gone = 0;
  const auto kept = ts::detail::without_small_parts(m.positions, m.indices, 1.0, 1000, gone);
  EXPECT_EQ(kept.size(), 12u);  // the last of four equal parts stays
}

TEST(SmallParts, ForestFirstLevelDropsItsStonesForItsTrees) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  const ts::Model m = ts::load_model(data + "/models_kenney_racing/decoration-forest.glb");
  const std::vector<ts::LodLevel> chain = ts::build_lod_chain(m);
  ASSERT_GE(chain.size(), 2u);
  // Parts of a level by their size: the 28 stones are under 0.35 m across
  // (radius), every tree part (cones, trunks), mound and the ground over it.
  auto parts = [](const ts::LodLevel& lv, double r) {
    double gone = 0;
    const auto kept = ts::detail::without_small_parts(lv.positions, lv.indices, r, SIZE_MAX, gone);
    return std::make_pair(lv.triangles() - kept.size() / 3, kept.size() / 3);
  };
  const auto [stones0, rest0] = parts(chain[0], 0.35);
  ASSERT_EQ(stones0, 28u * 18u) << "the forest model changed";
  const auto [stones1, rest1] = parts(chain[1], 0.35);
  EXPECT_EQ(stones1, 0u);
  // Half the triangles, nearly all of them on the rest: before, the stones
  // kept 10 triangles each (280 of 1002) and the rest had 722 of 1502.
  EXPECT_LE(chain[1].triangles(), m.triangles() / 2);
  EXPECT_GE(rest1, 950u);
  EXPECT_GT(double(rest1) / double(rest0), 0.6);
}
