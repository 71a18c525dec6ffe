// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "terrasprite/terrain/grid_mesh.h"
#include "terrasprite/terrain/pyramid.h"
#include "terrasprite/terrain/synth.h"

using namespace terrasprite;

TEST(Pyramid, LevelIndicesKeepEvery2kPlusLast) {
  EXPECT_EQ(level_indices(9, 0), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(level_indices(9, 2), (std::vector<int>{0, 4, 8}));
  EXPECT_EQ(level_indices(10, 2),
            (std::vector<int>{0, 4, 8, 9}));  // narrower last quad, nothing lost
  EXPECT_EQ(level_indices(1, 3), (std::vector<int>{0}));
  EXPECT_EQ(level_indices(2, 5), (std::vector<int>{0, 1}));
}

TEST(Pyramid, QuadIndicesForThePaperSetup) {
  std::vector<int> q = quad_indices(513, 16);
  ASSERT_EQ(q.size(), 17u);
  for (int i = 0; i <= 16; ++i) EXPECT_EQ(q[i], 32 * i);
  EXPECT_EQ(quad_indices(1201, 16).back(), 1200);
  EXPECT_EQ(quad_indices(5, 16).size(), 5u);  // clamped to n - 1 quads
}

TEST(Pyramid, LevelCountDownToOneQuad) {
  Heightfield h;
  h.width = h.height = 513;
  EXPECT_EQ(level_count(h, 1), 10);  // 512 .. 1 quads
  EXPECT_EQ(level_count(h, 16), 6);  // 512, 256, 128, 64, 32, 16
}

TEST(Mesh, CountsPerLevel) {
  SynthOptions s;
  s.size = 33;
  Heightfield h = synthesize_terrain(s);
  for (int level = 0; level < 5; ++level) {
    auto xs = level_indices(h.width, level);
    GridMesh m = build_grid_mesh(h, xs, xs);
    const int n = 32 >> level;
    EXPECT_EQ(m.columns, n + 1);
    EXPECT_EQ(m.vertices.size(), std::size_t((n + 1) * (n + 1) * 6));
    EXPECT_EQ(m.triangles(), 2LL * n * n);
  }
}

TEST(Mesh, TwoByTwoGridGeometryAndNormals) {
  Heightfield h;
  h.width = h.height = 2;
  h.spacing_x = 10;
  h.spacing_y = 20;
  h.heights = {0, 10, 0, 10};  // rises eastwards, 45 degrees
  std::vector<int> idx = {0, 1};
  GridMesh m = build_grid_mesh(h, idx, idx);
  ASSERT_EQ(m.indices.size(), 6u);
  EXPECT_FLOAT_EQ(m.vertices[0], -5.f);               // NW corner x
  EXPECT_FLOAT_EQ(m.vertices[1], 10.f);               // NW corner y
  EXPECT_NEAR(m.vertices[3], -std::sqrt(0.5), 1e-6);  // normal leans west
  EXPECT_NEAR(m.vertices[5], std::sqrt(0.5), 1e-6);
}

TEST(Mesh, GridSurfaceHeightIsTheDrawnTriangles) {
  SynthOptions s;
  s.size = 33;
  Heightfield h = synthesize_terrain(s);
  h.spacing_x = 30;
  h.spacing_y = 20;  // unequal, so an axis mix-up shows
  for (int quads : {32, 5}) {
    const auto xs = quad_indices(h.width, quads), ys = quad_indices(h.height, quads);
    const GridMesh m = build_grid_mesh(h, xs, ys);
    // Every triangle of the mesh: at its corners and at interior points the
    // height is the triangle's own plane.
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
      glm::dvec3 p[3];
      for (int k = 0; k < 3; ++k) {
        const float* v = &m.vertices[std::size_t(m.indices[t + k]) * 6];
        p[k] = {v[0], v[1], v[2]};
      }
      for (const glm::dvec3& w : {glm::dvec3(1, 0, 0), glm::dvec3(0.2, 0.3, 0.5),
                                  glm::dvec3(0.6, 0.3, 0.1), glm::dvec3(0.1, 0.1, 0.8)}) {
        const glm::dvec3 q = w.x * p[0] + w.y * p[1] + w.z * p[2];
        ASSERT_NEAR(grid_surface_height(h, xs, ys, q.x, q.y), q.z, 1e-3)
            << "quads " << quads << ", triangle " << t / 3;
      }
    }
    // Off the grid: its border.
    EXPECT_NEAR(grid_surface_height(h, xs, ys, 1e6, 1e6), h.at(h.width - 1, 0), 1e-3);
  }
  // The bilinear sampler is not the coarse grid's surface.
  const auto xs = quad_indices(h.width, 2), ys = quad_indices(h.height, 2);
  double worst = 0;
  for (double x = -400; x <= 400; x += 37)
    for (double y = -300; y <= 300; y += 29)
      worst = std::max(worst, std::abs(grid_surface_height(h, xs, ys, x, y) - h.sample(x, y)));
  EXPECT_GT(worst, 1.0);
}
