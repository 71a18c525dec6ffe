// SPDX-License-Identifier: MIT
// FLIP: analytic cases and agreement with the float64 reference implementation.
#include <gtest/gtest.h>

#include <algorithm>

#include "flip_reference.h"
#include "quality_test_util.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite::quality {
namespace {

using testing::flat;
using testing::flip_reference;
using testing::noisy;
using testing::scene;

// The colour-only FLIP of two flat colours, straight from the paper's formulas:
// filtering a flat image changes nothing and there are no features, so
// E = Ec = remap(HyAB(Hunt-Lab(c1), Hunt-Lab(c2)) ^ 0.7).
double flat_flip(std::array<std::uint8_t, 3> c1, std::array<std::uint8_t, 3> c2) {
  auto lin = [](std::uint8_t v) {
    const double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  using testing::ref::hunt_lab;
  using testing::ref::hyab;
  const double d = std::pow(hyab(hunt_lab(lin(c1[0]), lin(c1[1]), lin(c1[2])),
                                 hunt_lab(lin(c2[0]), lin(c2[1]), lin(c2[2]))),
                            0.7);
  const double cmax = std::pow(hyab(hunt_lab(0, 1, 0), hunt_lab(0, 0, 1)), 0.7);
  return d < 0.4 * cmax ? 0.95 / (0.4 * cmax) * d : 0.95 + (d - 0.4 * cmax) / (0.6 * cmax) * 0.05;
}

TEST(Flip, FlatColourChangeIsTheColourTermAlone) {
  const std::array<std::uint8_t, 3> pairs[][2] = {{{128, 128, 128}, {138, 128, 128}},
                                                  {{20, 40, 200}, {20, 60, 200}},
                                                  {{0, 255, 0}, {0, 0, 255}},
                                                  {{0, 0, 0}, {255, 255, 255}}};
  for (const auto& p : pairs) {
    const FlipResult f = flip(flat(48, 40, p[0]).view(), flat(48, 40, p[1]).view());
    const double expected = flat_flip(p[0], p[1]);
    EXPECT_NEAR(f.mean, expected, 2e-5)
        << int(p[0][0]) << "," << int(p[0][1]) << "," << int(p[0][2]);
    EXPECT_NEAR(f.median, expected, 2e-5);
  }
  // Green against blue is the remapping's maximum: exactly 1.
  EXPECT_NEAR(flat_flip({0, 255, 0}, {0, 0, 255}), 1.0, 1e-12);
}

TEST(Flip, EdgeShiftRaisesTheFeatureTerm) {
  // A vertical black/white edge moved by two pixels.
  Image a = flat(64, 48, {0, 0, 0}), b = a;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      if (x >= 30) std::fill(a.px(x, y), a.px(x, y) + 3, 255);
      if (x >= 32) std::fill(b.px(x, y), b.px(x, y) + 3, 255);
    }
  FlipOptions o;
  o.want_map = true;
  const FlipResult f = flip(a.view(), b.view(), o);
  const auto r = flip_reference(a, b);
  const int i = 20 * 64 + 31;  // in the shifted strip
  EXPECT_GT(r.feature[i], 0.3);
  EXPECT_GT(f.map[i], r.color[i] + 0.01);  // Ec^(1 - Ef) > Ec when Ef > 0
  EXPECT_NEAR(f.map[i], r.map[i], 1e-4);
  // Far from the edge nothing differs.
  EXPECT_EQ(f.map[20 * 64 + 2], 0.0f);
}

TEST(Flip, AgreesWithTheFloat64Reference) {
  struct Case {
    const char* name;
    Image a, b;
    double ppd;
  };
  const Image s = scene(96, 80, 4);
  Image shifted = s;
  for (int y = 0; y < 80; ++y)
    for (int x = 0; x < 96; ++x) std::copy_n(s.px(std::min(x + 1, 95), y), 3, shifted.px(x, y));
  const Case cases[] = {{"noise", s, noisy(s, 10), 67.02},
                        {"shift", s, shifted, 67.02},
                        {"noise, 30 ppd", s, noisy(s, 25, 3), 30},
                        {"colours", scene(70, 90, 8), scene(70, 90, 9), 67.02}};
  for (const Case& c : cases) {
    FlipOptions o;
    o.ppd = c.ppd;
    o.want_map = true;
    const FlipResult f = flip(c.a.view(), c.b.view(), o);
    const auto r = flip_reference(c.a, c.b, c.ppd);
    double worst = 0;
    for (std::size_t i = 0; i < r.map.size(); ++i)
      worst = std::max(worst, std::abs(f.map[i] - r.map[i]));
    EXPECT_NEAR(f.mean, r.mean, 1e-5) << c.name;
    EXPECT_LT(worst, 1e-3) << c.name;
    std::printf(
        "[flip reference] %-14s mean %.8f / %.8f (ours / float64 2D), worst pixel diff %.2e\n",
        c.name, f.mean, r.mean, worst);
  }
}

TEST(Flip, MedianAndMapConventions) {
  const Image a = scene(33, 21), b = noisy(a, 20);
  FlipOptions o;
  o.want_map = true;
  const FlipResult f = flip(a.view(), b.view(), o);
  ASSERT_EQ(f.map.size(), 33u * 21u);
  std::vector<float> v = f.map;
  std::sort(v.begin(), v.end());
  EXPECT_DOUBLE_EQ(f.median, v[v.size() / 2]);  // odd count
  double sum = 0;
  for (float x : f.map) sum += x;
  EXPECT_NEAR(f.mean, sum / f.map.size(), 1e-9);
  for (float x : f.map) EXPECT_TRUE(x >= 0 && x <= 1);
  EXPECT_TRUE(flip(a.view(), b.view()).map.empty());  // only when asked for
  // Even count: the mean of the two middle values.
  const Image c = scene(32, 20), d = noisy(c, 20);
  const FlipResult g = flip(c.view(), d.view(), o);
  std::vector<float> u = g.map;
  std::sort(u.begin(), u.end());
  EXPECT_DOUBLE_EQ(g.median, 0.5 * (double(u[u.size() / 2 - 1]) + u[u.size() / 2]));
}

}  // namespace
}  // namespace terrasprite::quality
