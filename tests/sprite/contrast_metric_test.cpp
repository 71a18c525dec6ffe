// SPDX-License-Identifier: MIT
// The contrast metric (ErrorMetric::kContrast): a keyframe's per-quad
// luminance gradient and deviation, and the predicted image error built from
// them and the exact reprojection error.
#include <gtest/gtest.h>

#include <cmath>

#include "sprite/keyframe_contrast.h"
#include "sprite_test_util.h"
#include "terrasprite/camera/frame.h"
#include "terrasprite/sprite/error_metric.h"

namespace terrasprite {
namespace {

using sprite_test::flat;
using sprite_test::overhead;

constexpr int kSize = 256;

std::vector<std::uint8_t> image(auto grey_at) {
  std::vector<std::uint8_t> rgba(std::size_t(kSize) * kSize * 4);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      std::uint8_t* p = &rgba[(std::size_t(y) * kSize + x) * 4];
      const int g = grey_at(x, y);
      p[0] = p[1] = p[2] = std::uint8_t(g < 0 ? 0 : g);
      p[3] = g < 0 ? 0 : 255;  // negative: keyframe sky (transparent black)
    }
  return rgba;
}

TEST(QuadContrast, UniformHasNoneARampHasItsSlopeAndSkyCountsAsSky) {
  Heightfield h = flat(65, 10.0);
  const CoarseGrid g = make_coarse_grid(h, 4);
  const Camera key = overhead(glm::dvec3(320, -320, 0), 1500.0);
  const QuadContrast uniform =
      quad_contrast(g, key, kSize, kSize, image([](int, int) { return 90; }));
  const QuadContrast ramp =
      quad_contrast(g, key, kSize, kSize, image([](int x, int) { return x / 2; }));
  const QuadContrast sky = quad_contrast(g, key, kSize, kSize, image([](int, int) { return -1; }));
  // Half sky: the left half transparent, the right half the sky's own grey.
  const int sky_grey =
      int(std::lround(0.2126 * kSkyColor[0] + 0.7152 * kSkyColor[1] + 0.0722 * kSkyColor[2]));
  const QuadContrast edge = quad_contrast(
      g, key, kSize, kSize, image([&](int x, int) { return x < kSize / 2 ? -1 : sky_grey; }));
  for (int q = 0; q < g.quad_count(); ++q) {
    EXPECT_EQ(uniform.gradient[q], 0.f) << q;
    EXPECT_EQ(uniform.deviation[q], 0.f) << q;
    EXPECT_EQ(sky.gradient[q], 0.f) << q;
    EXPECT_LT(edge.gradient[q], 0.5f) << q;  // within rounding of the sky's grey
    // x / 2 steps by 1 every other pixel: the central difference is 0.5 everywhere.
    EXPECT_NEAR(ramp.gradient[q], 0.5f, 1e-4) << q;
    EXPECT_GT(ramp.deviation[q], 1.f) << q;
  }
}

TEST(ContrastMetric, IsTheExactErrorTimesTheGradientCappedByTheDeviation) {
  Heightfield h = flat(65, 10.0);
  h.at(24, 24) = 20.f;  // only quad (1, 1) errs
  const CoarseGrid g = make_coarse_grid(h, 4);
  const glm::dvec3 C = g.centre[1 * 4 + 1];
  const Camera key = overhead(C, 3000.0);
  KeyframeSamples k =
      make_keyframe_samples(g, key, 512, 512, std::vector<std::uint8_t>(g.quad_count(), 1));
  Camera view = Camera::look_at(C + glm::dvec3(800, 240, 2500), C, 60.0, 1.0);
  view.near_m = 1.0;
  view.far_m = 1e5;
  EXPECT_EQ(sprite_error(g, k, view).contrast_levels, 0.0);  // no contrast measured: 0
  k.gradient.assign(g.quad_count(), 3.f);
  k.deviation.assign(g.quad_count(), 1000.f);
  const SpriteError e = sprite_error(g, k, view);
  ASSERT_GT(e.exact_px, 0.05);
  EXPECT_NEAR(e.contrast_levels, 3.0 * e.exact_px, 1e-9);
  EXPECT_EQ(e.value(ErrorMetric::kContrast), e.contrast_levels);
  // A shift past the texture's features errs by at most sqrt(2) x its deviation.
  k.deviation.assign(g.quad_count(), 0.01f);
  const double quad_error = 4.0 * e.exact_px;  // RMS over 16 samples, one of them nonzero
  ASSERT_GT(3.0 * quad_error, std::sqrt(2.0) * 0.01);
  EXPECT_NEAR(sprite_error(g, k, view).contrast_levels, std::sqrt(2.0) * 0.01f / 4.0, 1e-7);
}

}  // namespace
}  // namespace terrasprite
