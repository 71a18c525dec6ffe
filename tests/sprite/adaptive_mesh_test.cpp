// SPDX-License-Identifier: MIT
// The view-dependent coarse mesh: crack-free, within its triangle budget,
// fine near the camera and coarse far away, exact with no budget; and the
// sprite renderer drawing it.
#include "terrasprite/sprite/adaptive_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "sprite_test_util.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite {
namespace {

using namespace sprite_test;

// Low over the terrain's south edge, looking north across it.
Camera low_south_view(const Heightfield& h) {
  const double E = h.extent_y();
  Camera c = Camera::look_at(glm::dvec3(0, -0.45 * E, 1800), glm::dvec3(0, 0.2 * E, 0), 60.0, 1.0);
  fit_clip_planes(c, h);
  return c;
}

double cross2(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

// Every interior edge is shared by exactly two triangles (a T-junction or a
// crack leaves an edge used once away from the border); every triangle is
// counter-clockwise seen from above; together they cover the terrain once.
void expect_watertight(const CoarseGrid& g, const Heightfield& h) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  double area = 0;
  for (std::size_t t = 0; t < g.triangles.size(); t += 3) {
    const std::uint32_t v[3] = {g.triangles[t], g.triangles[t + 1], g.triangles[t + 2]};
    const double a = cross2(g.mesh_vertices[v[0]], g.mesh_vertices[v[1]], g.mesh_vertices[v[2]]);
    EXPECT_GT(a, 0) << "triangle " << t / 3 << " not counter-clockwise";
    area += a / 2;
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t p = v[e], q = v[(e + 1) % 3];
      ++uses[{std::min(p, q), std::max(p, q)}];
    }
  }
  EXPECT_NEAR(area, h.extent_x() * h.extent_y(), 1e-6 * h.extent_x() * h.extent_y());
  const double x0 = h.world_x(0), x1 = h.world_x(h.width - 1), y0 = h.world_y(h.height - 1),
               y1 = h.world_y(0);
  auto on_border = [&](glm::dvec3 p) { return p.x == x0 || p.x == x1 || p.y == y0 || p.y == y1; };
  int open = 0;
  for (const auto& [edge, n] : uses) {
    const glm::dvec3 a = g.mesh_vertices[edge.first], b = g.mesh_vertices[edge.second];
    EXPECT_LE(n, 2);
    if (n == 1) {
      ++open;
      const bool border = on_border(a) && on_border(b) && (a.x == b.x || a.y == b.y) &&
                          (a.x == x0 || a.x == x1 || a.y == y0 || a.y == y1);
      EXPECT_TRUE(border) << "open edge inside the terrain: (" << a.x << ", " << a.y << ") - ("
                          << b.x << ", " << b.y << ")";
    }
  }
  EXPECT_GE(open, 4);
  // Vertices are samples of the field, so shared edges match in height too.
  for (const glm::dvec3& p : g.mesh_vertices) {
    const int i = int(std::lround(p.x / h.spacing_x + (h.width - 1) * 0.5));
    const int j = int(std::lround((h.height - 1) * 0.5 - p.y / h.spacing_y));
    EXPECT_EQ(p.z, double(h.at(i, j)));
  }
}

TEST(AdaptiveMesh, CrackFreeAndWithinItsBudget) {
  const Terrain t = small_mountains();
  const AdaptiveMesher mesher(t.heights);
  EXPECT_EQ(mesher.levels(), 7);  // 129 samples: down to single-sample cells
  const Camera c = low_south_view(t.heights);
  for (long long budget : {2LL, 50LL, 512LL, 2000LL}) {
    const CoarseGrid g = mesher.build(c, 64, 64, {.triangle_budget = budget});
    SCOPED_TRACE(budget);
    EXPECT_LE(g.triangle_count(), budget);
    EXPECT_GE(g.triangle_count(), std::min(budget, 2000LL) * 8 / 10);  // spends it
    EXPECT_TRUE(g.adaptive);
    ASSERT_EQ(g.cell_first.size(), std::size_t(g.quad_count()) + 1);
    EXPECT_EQ(g.cell_first.back(), int(g.triangles.size()));
    expect_watertight(g, t.heights);
  }
}

TEST(AdaptiveMesh, FineNearTheCameraCoarseFarAway) {
  const Terrain t = small_mountains();
  const Heightfield& h = t.heights;
  const AdaptiveMesher mesher(h);
  const Camera c = low_south_view(h);
  const CoarseGrid g = mesher.build(c, 64, 64, {.triangle_budget = 800});
  // Cells in view, nearest first: the nearest quarter's mean area (samples^2)
  // is well under the farthest quarter's.
  std::vector<std::pair<double, double>> by_distance;  // (distance, area)
  for (int q = 0; q < g.quad_count(); ++q) {
    const auto [x0, y0, x1, y1] = g.cell_rect[q];
    const glm::dvec3 centre(h.world_x(0.5 * (x0 + x1)), h.world_y(0.5 * (y0 + y1)),
                            h.at((x0 + x1) / 2, (y0 + y1) / 2));
    glm::dvec2 px;
    if (!project_to_pixel(c, 64, 64, centre, px) || px.x < 0 || px.x > 64 || px.y < 0 || px.y > 64)
      continue;
    by_distance.emplace_back(glm::length(centre - c.position), double(x1 - x0) * (y1 - y0));
  }
  ASSERT_GE(by_distance.size(), 40u);
  std::sort(by_distance.begin(), by_distance.end());
  const std::size_t quarter = by_distance.size() / 4;
  double near_area = 0, far_area = 0;
  for (std::size_t k = 0; k < quarter; ++k) {
    near_area += by_distance[k].second;
    far_area += by_distance[by_distance.size() - 1 - k].second;
  }
  EXPECT_GT(far_area, 4 * near_area);
}

TEST(AdaptiveMesh, NoBudgetAndNoToleranceIsTheFullField) {
  Terrain t;
  t.heights = synthesize_terrain({.size = 33, .spacing_m = 30.0, .relief_m = 600.0});
  const Heightfield& h = t.heights;
  const AdaptiveMesher mesher(h);
  const CoarseGrid g =
      mesher.build(low_south_view(h), 64, 64, {.triangle_budget = 1LL << 40, .tolerance_px = 0});
  expect_watertight(g, h);
  // Every sample, interpolated on the triangle over it, is the field's height.
  double worst = 0;
  for (int j = 0; j < h.height; ++j)
    for (int i = 0; i < h.width; ++i) {
      const glm::dvec3 p(h.world_x(i), h.world_y(j), 0);
      bool found = false;
      for (std::size_t k = 0; k < g.triangles.size() && !found; k += 3) {
        const glm::dvec3 a = g.mesh_vertices[g.triangles[k]],
                         b = g.mesh_vertices[g.triangles[k + 1]],
                         d = g.mesh_vertices[g.triangles[k + 2]];
        const double area = cross2(a, b, d), u = cross2(a, p, d) / area, v = cross2(a, b, p) / area;
        if (u < -1e-9 || v < -1e-9 || u + v > 1 + 1e-9) continue;
        found = true;
        worst = std::max(worst, std::abs(a.z + u * (b.z - a.z) + v * (d.z - a.z) - h.at(i, j)));
      }
      EXPECT_TRUE(found) << i << "," << j;
    }
  EXPECT_LT(worst, 1e-3);
  for (double d : g.max_deviation) EXPECT_LT(d, 1e-3);
}

// The sprite renderer with the adaptive mesh: each keyframe has its own
// mesh within the budget, its own camera's sprite is the keyframe, and the
// error the trigger reads is measured on the mesh drawn.
TEST(AdaptiveMesh, SpriteRendererDrawsTheKeyframesMesh) {
  GlContext gl;
  const Terrain t = small_mountains();
  Scene scene(t);
  SpriteOptions o;
  o.lod_quads = 8;  // budget 2 x 8^2 = 128 triangles
  o.mesh = CoarseMesh::kAdaptive;
  o.sharp_px = 0;
  SpriteRenderer r(scene, 64, 64, o);
  EXPECT_EQ(r.mesh_budget(), 128);
  const std::vector<Camera> path = paper_path(t.heights, 12, 1.0);
  r.render_keyframe(path[0]);
  const CoarseGrid& g0 = r.grid();
  ASSERT_TRUE(g0.adaptive);
  EXPECT_LE(g0.triangle_count(), 128);
  EXPECT_EQ(r.fallback_quads().size(), std::size_t(g0.quad_count()));
  EXPECT_EQ(r.error(path[0]).paper_px, 0.0);
  const Frame key = r.render_keyframe(path[0]);
  const Frame same = r.render_sprite(path[0]);
  EXPECT_EQ(same.cls, FrameClass::kSprite);
  EXPECT_EQ(same.triangles, r.grid().triangle_count());
  EXPECT_GT(psnr(key.color, same.color), 30.0);
  const std::uint64_t first = r.grid().serial;
  r.render_keyframe(path[11]);
  EXPECT_NE(r.grid().serial, first);  // a new keyframe, a new mesh for its camera
  EXPECT_EQ(std::string(to_string(CoarseMesh::kAdaptive)), "adaptive");
}

}  // namespace
}  // namespace terrasprite
