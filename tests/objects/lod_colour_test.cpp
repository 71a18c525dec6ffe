// SPDX-License-Identifier: MIT
// LOD chain colours: sloppy levels keep each triangle on its own UV island
// (palette atlases: one flat swatch per colour), on a model made in code and
// on the Kenney forest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "object_test_util.h"
#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/model.h"

namespace ts = terrasprite;

namespace {

// Island A: uv in [0.05, 0.15]^2; island B: uv in [0.85, 0.95]^2.
constexpr float kIslandLo[2] = {0.05f, 0.85f};
constexpr float kIslandSize = 0.1f;

// k x k separate small quads in a wavy sheet 1 m across, island A and B in a
// checkerboard: neighbours in space are far apart in uv. Separate quads are all
// open border, so meshopt_simplify stalls and the chain goes sloppy at once.
ts::Model checkerboard_quads(int k) {
  ts::Model m;
  m.name = "checkerboard";
  const float cell = 1.f / float(k), q = 0.8f * cell;
  for (int y = 0; y < k; ++y)
    for (int x = 0; x < k; ++x) {
      const int island = (x + y) % 2;
      const auto base = std::uint32_t(m.positions.size());
      for (int c = 0; c < 4; ++c) {
        const float px = float(x) * cell + ((c & 1) ? q : 0.f) - 0.5f;
        const float py = float(y) * cell + ((c & 2) ? q : 0.f) - 0.5f;
        m.positions.emplace_back(px, py, 0.1f + 0.05f * std::sin(6.f * px) * std::cos(5.f * py));
        m.normals.emplace_back(0.f, 0.f, 1.f);
        m.uvs.emplace_back(kIslandLo[island] + ((c & 1) ? kIslandSize : 0.f),
                           kIslandLo[island] + ((c & 2) ? kIslandSize : 0.f));
      }
      for (std::uint32_t i : {0u, 1u, 3u, 0u, 3u, 2u}) m.indices.push_back(base + i);
    }
  m.parts.push_back({0, std::uint32_t(m.indices.size()), 0});
  m.materials.push_back({"atlas", glm::vec4(1.f), -1});
  m.normals_from_file = true;
  m.bounds_min = glm::vec3(-0.5f, -0.5f, 0.f);
  m.bounds_max = glm::vec3(0.5f, 0.5f, 0.2f);
  return m;
}

int island_of(glm::vec2 uv) {
  for (int i = 0; i < 2; ++i)
    if (uv.x >= kIslandLo[i] - 1e-6f && uv.x <= kIslandLo[i] + kIslandSize + 1e-6f &&
        uv.y >= kIslandLo[i] - 1e-6f && uv.y <= kIslandLo[i] + kIslandSize + 1e-6f)
      return i;
  return -1;
}

// The Kenney colormap's swatch under uv: the 512 x 512 atlas is 16 columns of
// 32 px by 4 rows of 128 px, each a vertical gradient of one colour.
int swatch_of(glm::vec2 uv) {
  const auto cell = [](float f, int n) {
    return std::clamp(int(std::floor((f - std::floor(f)) * float(n))), 0, n - 1);
  };
  return cell(uv.y, 4) * 16 + cell(uv.x, 16);
}

}  // namespace

// Run time ~0.1 s.
TEST(LodChainColour, SloppyLevelsKeepUvIslands) {
  const ts::Model m = checkerboard_quads(32);
  const std::vector<ts::LodLevel> chain = ts::build_lod_chain(m);
  ASSERT_GE(chain.size(), 3u);
  std::size_t sloppy = 0;
  for (std::size_t l = 1; l < chain.size(); ++l) {
    const ts::LodLevel& lv = chain[l];
    sloppy += lv.sloppy;
    EXPECT_LT(lv.triangles(), chain[l - 1].triangles()) << "level " << l;
    EXPECT_GE(lv.error_m, chain[l - 1].error_m) << "level " << l;
    std::size_t crossing = 0, islands[2] = {0, 0};
    for (std::size_t t = 0; t < lv.triangles(); ++t) {
      const int a = island_of(lv.uvs[lv.indices[3 * t]]);
      const int b = island_of(lv.uvs[lv.indices[3 * t + 1]]);
      const int c = island_of(lv.uvs[lv.indices[3 * t + 2]]);
      ASSERT_GE(a, 0) << "level " << l << ": a uv outside both islands";
      crossing += a != b || a != c;
      ++islands[a];
    }
    EXPECT_EQ(crossing, 0u) << "level " << l << " (" << lv.triangles() << " triangles)";
    // Neither colour vanishes while the level has triangles to share.
    if (lv.triangles() >= 16) {
      EXPECT_GT(islands[0], 0u) << "level " << l;
      EXPECT_GT(islands[1], 0u) << "level " << l;
    }
  }
  EXPECT_GE(sloppy, 2u);
}

// The forest at checkpoint E (2006 triangles, a 512 x 512 palette atlas): on
// every level, the share of triangles whose corners lie in different swatches.
// Run time ~0.5 s.
TEST(LodChainColour, ForestSwatches) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  const ts::Model m = tstest::forest_10m(data);
  const std::vector<ts::LodLevel> chain = ts::build_lod_chain(m);
  for (std::size_t l = 0; l < chain.size(); ++l) {
    const ts::LodLevel& lv = chain[l];
    double area = 0.0, mixed_area = 0.0;
    std::size_t mixed = 0;
    for (const ts::MeshPart& p : lv.parts)
      for (std::uint32_t i = p.first_index; i < p.first_index + p.index_count; i += 3) {
        const std::uint32_t v[3] = {lv.indices[i], lv.indices[i + 1], lv.indices[i + 2]};
        const double a = 0.5 * glm::length(glm::cross(lv.positions[v[1]] - lv.positions[v[0]],
                                                      lv.positions[v[2]] - lv.positions[v[0]]));
        const int s0 = swatch_of(lv.uvs[v[0]]);
        const bool differs = swatch_of(lv.uvs[v[1]]) != s0 || swatch_of(lv.uvs[v[2]]) != s0;
        area += a;
        mixed += differs;
        mixed_area += differs ? a : 0.0;
      }
    std::printf(
        "forest level %zu: %zu triangles, sloppy %d, error %.3f m, mixed-swatch "
        "triangles %zu (%.1f%% of area)\n",
        l, lv.triangles(), int(lv.sloppy), lv.error_m, mixed, 100.0 * mixed_area / area);
    EXPECT_LE(mixed_area, 0.01 * area) << "level " << l;
  }
}
