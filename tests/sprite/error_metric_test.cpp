// SPDX-License-Identifier: MIT
// The LOD-sprite error metric (Eq. 1-2) on the CPU: still cameras, an
// analytic bump, growth with movement.
#include <gtest/gtest.h>

#include <cmath>

#include "sprite_test_util.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/sprite/error_metric.h"
#include "terrasprite/terrain/synth.h"

namespace terrasprite {
namespace {

using sprite_test::flat;
using sprite_test::overhead;

std::vector<std::uint8_t> all_visible(const CoarseGrid& g) {
  return std::vector<std::uint8_t>(g.quad_count(), 1);
}

TEST(CoarseGrid, CentresAreFullResolutionVerticesInsideQuads) {
  Heightfield h = flat(65, 10.0);
  CoarseGrid g = make_coarse_grid(h, 4);
  ASSERT_EQ(g.quads_x, 4);
  ASSERT_EQ(g.quad_count(), 16);
  EXPECT_EQ(g.xs, (std::vector<int>{0, 16, 32, 48, 64}));
  EXPECT_DOUBLE_EQ(g.centre[0].x, h.world_x(8));
  EXPECT_DOUBLE_EQ(g.centre[0].y, h.world_y(8));
  for (auto b : g.has_centre) EXPECT_EQ(b, 1);
  // One sample per quad: no vertex strictly inside.
  CoarseGrid fine = make_coarse_grid(flat(5, 1.0), 4);
  for (auto b : fine.has_centre) EXPECT_EQ(b, 0);
}

TEST(ErrorMetric, StillCameraHasZeroError) {
  SynthOptions so;
  so.size = 65;
  Heightfield h = synthesize_terrain(so);
  CoarseGrid g = make_coarse_grid(h, 4);
  for (int frame : {0, 100, 250, 400}) {
    Camera key = paper_path(h, 460, 1.0)[frame];
    KeyframeSamples k = make_keyframe_samples(g, key, 256, 256, all_visible(g));
    SpriteError e = sprite_error(g, k, key);
    EXPECT_GT(e.samples, 0) << frame;
    EXPECT_NEAR(e.paper_px, 0.0, 1e-5) << frame;  // acos rounding of beta
    EXPECT_NEAR(e.exact_px, 0.0, 1e-6) << frame;
  }
}

// A flat plane with one raised full-resolution sample at a quad centre C,
// seen straight down by the keyframe: C' lies exactly b below C. From a new
// eye looking at C, the displacement subtends the angle between C and C'.
TEST(ErrorMetric, BumpGivesTheAnalyticPixelError) {
  Heightfield h = flat(65, 10.0);
  const double b = 20.0;
  h.at(24, 24) = float(b);  // centre of quad (1, 1): samples 16..32
  CoarseGrid g = make_coarse_grid(h, 4);
  const int q = 1 * 4 + 1;
  const glm::dvec3 C = g.centre[q];
  ASSERT_DOUBLE_EQ(C.z, b);
  EXPECT_NEAR(g.edge_offset[q], b, 1e-9);
  const int size = 512;
  Camera key = overhead(C, 3000.0);
  KeyframeSamples k = make_keyframe_samples(g, key, size, size, all_visible(g));
  EXPECT_NEAR(glm::length(k.c_prime[q] - (C - glm::dvec3(0, 0, b))), 0.0, 1e-6);

  for (double side : {200.0, 800.0, 2000.0}) {
    Camera view = Camera::look_at(C + glm::dvec3(side, 0.3 * side, 2500.0), C, 60.0, 1.0);
    view.near_m = 1.0;
    view.far_m = 1e5;
    SpriteError e = sprite_error(g, k, view);
    ASSERT_EQ(e.samples, 16) << side;  // every centre in view, all visible
    const glm::dvec3 a = glm::normalize(C - view.position);
    const glm::dvec3 a2 = glm::normalize(C - glm::dvec3(0, 0, b) - view.position);
    const double theta = std::acos(std::clamp(glm::dot(a, a2), -1.0, 1.0));
    // Paper: angle / pixel angle. Only this quad errs, so RMS = its error / sqrt(16).
    const double paper = theta / view.pixel_angle(size);
    EXPECT_NEAR(e.paper_px * 4.0, paper, 1e-6 * paper) << side;
    // Exact: C projects to the image centre, C' at focal length * tan(theta).
    const double focal_px = 0.5 * size / std::tan(glm::radians(view.fov_y_deg) * 0.5);
    const double exact = focal_px * std::tan(theta);
    EXPECT_NEAR(e.exact_px * 4.0, exact, 1e-4 * exact) << side;
    EXPECT_GT(exact, 0.1);
  }
}

TEST(ErrorMetric, GrowsWithCameraMovement) {
  SynthOptions so;
  so.size = 129;
  Heightfield h = synthesize_terrain(so);
  CoarseGrid g = make_coarse_grid(h, 16);
  auto path = paper_path(h, 460, 1.0);
  for (int start : {30, 150, 300, 380}) {
    KeyframeSamples k = make_keyframe_samples(g, path[start], 512, 512, all_visible(g));
    double prev_paper = 0, prev_exact = 0;
    for (int step : {1, 3, 6, 12}) {
      SpriteError e = sprite_error(g, k, path[start + step]);
      EXPECT_GT(e.paper_px, prev_paper) << start << "+" << step;
      EXPECT_GT(e.exact_px, prev_exact) << start << "+" << step;
      prev_paper = e.paper_px;
      prev_exact = e.exact_px;
    }
  }
}

TEST(ErrorMetric, OnlyVisibleCentresCount) {
  Heightfield h = flat(65, 10.0);
  h.at(24, 24) = 20.f;
  CoarseGrid g = make_coarse_grid(h, 4);
  auto vis = all_visible(g);
  vis[5] = 0;  // the bump's quad hidden in the keyframe
  Camera key = overhead(g.centre[5], 3000.0);
  KeyframeSamples k = make_keyframe_samples(g, key, 256, 256, vis);
  Camera view = Camera::look_at(g.centre[5] + glm::dvec3(800, 0, 2500), g.centre[5], 60.0, 1.0);
  SpriteError e = sprite_error(g, k, view);
  EXPECT_EQ(e.samples, 15);
  EXPECT_EQ(e.in_view, 16);
  EXPECT_NEAR(e.fallback_fraction(), 1.0 / 16, 1e-12);
  EXPECT_NEAR(e.exact_px, 0.0, 1e-9);
}

// A bump of b = 20 m at the centre C of quad q of a flat 4 x 4 grid; the
// distance from C at which, edge-on, it moves a 512-pixel image 2 pixels.
struct OneBump {
  static constexpr double b = 20.0;
  static constexpr int q = 1 * 4 + 1, size = 512;
  CoarseGrid g;
  glm::dvec3 C;
  double two_px_distance;
  OneBump() {
    Heightfield h = flat(65, 10.0);
    h.at(24, 24) = float(b);
    g = make_coarse_grid(h, 4);
    C = g.centre[q];
    two_px_distance = b / (2.0 * overhead(C, 3000.0).pixel_angle(size));
  }
};

// The drape moves the image by b's component across the ray, none from
// straight above, all of it edge-on.
TEST(SharpDrape, DeviationCountsAcrossTheViewRay) {
  const OneBump bump;
  const CoarseGrid& g = bump.g;
  const glm::dvec3 C = bump.C;
  const int q = bump.q, size = bump.size;
  ASSERT_DOUBLE_EQ(g.max_deviation[q], bump.b);
  EXPECT_TRUE(drape_is_sharp(g, q, overhead(C, 3000.0), size, 1e-3));
  const double D = bump.two_px_distance;
  const Camera edge_on = Camera::look_at(C + glm::dvec3(D, 0, 0), C, 60.0, 1.0);
  EXPECT_FALSE(drape_is_sharp(g, q, edge_on, size, 1.9));
  EXPECT_TRUE(drape_is_sharp(g, q, edge_on, size, 2.1));
  // From 60 degrees up: half of it (cos 60).
  const double up = glm::radians(60.0);
  const Camera steep =
      Camera::look_at(C + D * glm::dvec3(std::cos(up), 0, std::sin(up)), C, 60.0, 1.0);
  EXPECT_FALSE(drape_is_sharp(g, q, steep, size, 0.95));
  EXPECT_TRUE(drape_is_sharp(g, q, steep, size, 1.05));
}

// The view's drape error: the RMS over the in-view cells of each cell's
// drape_displacement_px. One bump in one cell moves plain LOD's image by
// 2 px edge-on, the other cells by nothing; from straight above by nothing.
TEST(ErrorMetric, DrapePxIsTheRmsDrapeDisplacementOverTheView) {
  const OneBump bump;
  const CoarseGrid& g = bump.g;
  const glm::dvec3 C = bump.C;
  const int q = bump.q, size = bump.size;
  const double D = bump.two_px_distance;
  const Camera edge_on = Camera::look_at(C + glm::dvec3(D, 0, 0), C, 60.0, 1.0);
  EXPECT_NEAR(drape_displacement_px(g, q, edge_on, size), 2.0, 1e-9);
  KeyframeSamples k = make_keyframe_samples(g, edge_on, size, size, all_visible(g));
  const SpriteError e = sprite_error(g, k, edge_on);
  ASSERT_GT(e.in_view, 1);
  EXPECT_NEAR(e.drape_px, 2.0 / std::sqrt(double(e.in_view)), 1e-9);
  // Cells hidden in the keyframe count too: the drape error is the view's.
  std::vector<std::uint8_t> none(g.quad_count(), 0);
  KeyframeSamples hidden = make_keyframe_samples(g, edge_on, size, size, none);
  EXPECT_DOUBLE_EQ(sprite_error(g, hidden, edge_on).drape_px, e.drape_px);
  const Camera above = overhead(C, 3000.0);
  EXPECT_NEAR(
      sprite_error(g, make_keyframe_samples(g, above, size, size, all_visible(g)), above).drape_px,
      0.0, 1e-9);
}

TEST(ErrorMetric, ResampleScaleIsTheChangeInPixelFootprint) {
  Heightfield h = flat(65, 10.0);
  CoarseGrid g = make_coarse_grid(h, 4);
  Camera key = overhead(glm::dvec3(0), 1000.0);
  KeyframeSamples k = make_keyframe_samples(g, key, 256, 256, all_visible(g));
  EXPECT_NEAR(sprite_error(g, k, key).resample_scale, 1.0, 1e-9);
  // Straight down over a plane every pixel's footprint grows with the height:
  // twice as high, each keyframe pixel covers half as many new pixels per side.
  EXPECT_NEAR(sprite_error(g, k, overhead(glm::dvec3(0), 2000.0)).resample_scale, 2.0, 1e-6);
  EXPECT_NEAR(sprite_error(g, k, overhead(glm::dvec3(0), 500.0)).resample_scale, 2.0, 1e-6);
}

// A keyframe supersampled 1.5 times (384 pixels for a 256-pixel view, same
// field of view): from its own camera nothing is stretched; closing in
// 1.5 times only undoes the supersampling; 3 times stretches 2 times; and
// moving away shrinks it past its supersampling only beyond 1 / 1.5.
TEST(ErrorMetric, ASupersampledKeyframeIsStretchedOnlyPastItsDensity) {
  Heightfield h = flat(65, 10.0);
  CoarseGrid g = make_coarse_grid(h, 4);
  Camera key = overhead(glm::dvec3(0), 1200.0);
  KeyframeSamples k = make_keyframe_samples(g, key, 384, 384, all_visible(g), 256, 256);
  EXPECT_NEAR(k.supersample, 1.5, 1e-12);
  EXPECT_NEAR(sprite_error(g, k, key).resample_scale, 1.0, 1e-9);
  EXPECT_NEAR(sprite_error(g, k, overhead(glm::dvec3(0), 800.0)).resample_scale, 1.0, 1e-6);
  EXPECT_NEAR(sprite_error(g, k, overhead(glm::dvec3(0), 400.0)).resample_scale, 2.0, 1e-6);
  EXPECT_NEAR(sprite_error(g, k, overhead(glm::dvec3(0), 2400.0)).resample_scale, 2.0, 1e-6);
  EXPECT_NEAR(sprite_error(g, k, overhead(glm::dvec3(0), 400.0)).resample_aniso, 2.0, 1e-4);
  EXPECT_NEAR(sprite_error(g, k, key).resample_aniso, 1.0, 1e-6);
  // The paper metric's pixel is the view's: the same motion errs as many view pixels either way.
  KeyframeSamples plain = make_keyframe_samples(g, key, 256, 256, all_visible(g));
  Camera moved = overhead(glm::dvec3(30, 0, 0), 1200.0);
  EXPECT_NEAR(sprite_error(g, k, moved).exact_px, sprite_error(g, plain, moved).exact_px, 1e-9);
}

// Over a plane seen at 60 degrees incidence from the key's distance, the
// keyframe is shrunk by cos 60 = 1/2 along one axis and kept along the
// other: the area's mean reads sqrt 2, the worst axis 2. A pure change of
// height scales both axes alike, so both read the same.
TEST(ErrorMetric, AnisotropicScaleReadsTheWorstAxis) {
  Heightfield h = flat(65, 10.0);
  CoarseGrid g = make_coarse_grid(h, 4);
  Camera key = overhead(glm::dvec3(0), 1000.0);
  KeyframeSamples k = make_keyframe_samples(g, key, 256, 256, all_visible(g));
  EXPECT_NEAR(sprite_error(g, k, key).resample_aniso, 1.0, 1e-6);
  EXPECT_NEAR(sprite_error(g, k, overhead(glm::dvec3(0), 2000.0)).resample_aniso, 2.0, 1e-4);
  const double a = glm::radians(60.0);
  Camera tilted = Camera::look_at(glm::dvec3(0, -1000.0 * std::sin(a), 1000.0 * std::cos(a)),
                                  glm::dvec3(0), 60.0, 1.0);
  tilted.near_m = 1.0;
  tilted.far_m = 1e5;
  const SpriteError e = sprite_error(g, k, tilted);
  ASSERT_GT(e.samples, 8);
  EXPECT_NEAR(e.resample_scale, std::sqrt(2.0), 0.15);
  EXPECT_NEAR(e.resample_aniso, 2.0, 0.25);
  EXPECT_GT(e.resample_aniso, 1.25 * e.resample_scale);
}

TEST(Visibility, DepthBufferHidesPointsBehindNearerSurface) {
  Camera key = overhead(glm::dvec3(0), 1000.0);
  std::vector<float> depth(64 * 64, 1000.f);
  DepthView dv{depth, 64, 64};
  EXPECT_TRUE(visible_in_keyframe(key, dv, glm::dvec3(0, 0, 0)));
  EXPECT_TRUE(visible_in_keyframe(key, dv, glm::dvec3(10, 0, 100)));    // in front of the surface
  EXPECT_FALSE(visible_in_keyframe(key, dv, glm::dvec3(10, 0, -100)));  // behind it
  EXPECT_FALSE(visible_in_keyframe(key, dv, glm::dvec3(5000, 0, 0)));   // outside the view
  EXPECT_FALSE(visible_in_keyframe(key, dv, glm::dvec3(0, 0, 2000)));   // behind the eye
}

}  // namespace
}  // namespace terrasprite
