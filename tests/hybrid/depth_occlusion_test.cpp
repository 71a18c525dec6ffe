// SPDX-License-Identifier: MIT
// DepthOcclusion and sphere_on_screen on depth buffers made in code (no GL):
// the rectangle holds every point of the sphere, the pyramid's answer equals
// a pixel-by-pixel check, and nothing at the near plane or in front of the
// depth is ever hidden. About 0.1 s.
#include "terrasprite/hybrid/depth_occlusion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace ts = terrasprite;

namespace {

constexpr int kW = 97, kH = 61;  // odd sizes: the pyramid's edge blocks

ts::Camera camera() {
  return ts::Camera::look_at({0, 0, 0}, {0, 100, 0}, 60, double(kW) / kH);
}

/// Reversed-Z depth of a point `z_m` metres along the view axis.
float raw_depth(const ts::Camera& c, double z_m) {
  return float(c.near_m * (c.far_m - z_m) / (z_m * (c.far_m - c.near_m)));
}

/// Window position (pixels, row 0 at the bottom) of a world point in front of the eye.
glm::dvec2 window(const ts::Camera& c, glm::dvec3 p) {
  const glm::dvec3 to = p - c.position;
  const double z = glm::dot(to, c.forward());
  const double ty = std::tan(glm::radians(c.fov_y_deg) / 2), tx = ty * c.aspect;
  return {(glm::dot(to, c.right()) / (z * tx) + 1) / 2 * kW,
          (glm::dot(to, c.up()) / (z * ty) + 1) / 2 * kH};
}

/// Pixel-by-pixel: every pixel of the rectangle nearer than the sphere.
bool hidden_brute(const ts::Camera& c, const std::vector<float>& raw, const ts::SphereOnScreen& s) {
  if (s.straddles_near || s.rect.empty()) return false;
  const float t = raw_depth(c, s.nearest_depth_m);
  for (int y = s.rect.y0; y <= s.rect.y1; ++y)
    for (int x = s.rect.x0; x <= s.rect.x1; ++x)
      if (!(raw[std::size_t(y) * kW + x] > t)) return false;
  return true;
}

TEST(DepthOcclusion, TheRectangleHoldsEveryPointOfTheSphere) {
  const ts::Camera c = camera();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  for (int k = 0; k < 300; ++k) {
    const glm::dvec3 centre(60 * u(rng), 20 + 80 * (u(rng) + 1), 40 * u(rng));
    const double r = 0.5 + 10 * (u(rng) + 1);
    const ts::SphereOnScreen s = ts::sphere_on_screen(c, kW, kH, centre, r);
    if (s.straddles_near) continue;
    double x_lo = 1e9, x_hi = -1e9, y_lo = 1e9, y_hi = -1e9;
    for (int i = 0; i < 4000; ++i) {
      const glm::dvec3 d = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
      const glm::dvec2 w = window(c, centre + r * d);
      x_lo = std::min(x_lo, w.x), x_hi = std::max(x_hi, w.x);
      y_lo = std::min(y_lo, w.y), y_hi = std::max(y_hi, w.y);
      if (w.x < 0 || w.x >= kW || w.y < 0 || w.y >= kH) continue;
      ASSERT_GE(int(w.x), s.rect.x0) << k;
      ASSERT_LE(int(w.x), s.rect.x1) << k;
      ASSERT_GE(int(w.y), s.rect.y0) << k;
      ASSERT_LE(int(w.y), s.rect.y1) << k;
    }
    // And it is tight: at most the one-pixel margin (and a pixel of the
    // sampling's shortfall) beyond the sampled extent, where that is inside.
    if (x_lo > 2 && x_hi < kW - 3 && y_lo > 2 && y_hi < kH - 3) {
      EXPECT_GE(s.rect.x0, int(x_lo) - 2) << k;
      EXPECT_LE(s.rect.x1, int(x_hi) + 2) << k;
      EXPECT_GE(s.rect.y0, int(y_lo) - 2) << k;
      EXPECT_LE(s.rect.y1, int(y_hi) + 2) << k;
      ++tested;
    }
  }
  EXPECT_GT(tested, 50);
}

TEST(DepthOcclusion, AHugeSphereJustPastTheNearPlaneStaysInTheImage) {
  // Its nearest point 1.5 m ahead, far to the side: tangent slopes of ~1e12,
  // ~1e13 pixels: clamped, never an int overflow.
  const ts::Camera c = camera();
  const ts::SphereOnScreen s = ts::sphere_on_screen(c, kW, kH, {1e12, 1e9 + 1.5, 0}, 1e9);
  ASSERT_FALSE(s.straddles_near);
  EXPECT_GE(s.rect.x0, 0);
  EXPECT_LE(s.rect.x1, kW - 1);
  EXPECT_GE(s.rect.y0, 0);
  EXPECT_LE(s.rect.y1, kH - 1);
}

TEST(DepthOcclusion, AWallHidesWhatIsBehindItOnly) {
  const ts::Camera c = camera();
  std::vector<float> raw(std::size_t(kW) * kH, raw_depth(c, 50));
  const ts::DepthOcclusion wall(raw, kW, kH, c);
  auto at = [&](double y_m, double r) { return ts::sphere_on_screen(c, kW, kH, {0, y_m, 0}, r); };
  EXPECT_TRUE(wall.hidden(at(80, 5)));
  EXPECT_TRUE(wall.hidden(at(56, 5)));    // nearest point 51 m
  EXPECT_FALSE(wall.hidden(at(54, 5)));   // nearest point 49 m: in front of the wall
  EXPECT_FALSE(wall.hidden(at(30, 2)));   // wholly in front
  EXPECT_FALSE(wall.hidden(at(0, 5)));    // around the eye
  EXPECT_FALSE(wall.hidden(at(3, 2.5)));  // through the near plane
  // Nothing drawn: nothing hides.
  EXPECT_FALSE(ts::DepthOcclusion().hidden(at(80, 5)));
  const ts::DepthOcclusion sky(std::vector<float>(raw.size(), 0.0f), kW, kH, c);
  EXPECT_FALSE(sky.hidden(at(80, 5)));
  EXPECT_THROW(ts::DepthOcclusion(raw, kW + 1, kH, c), std::invalid_argument);
}

TEST(DepthOcclusion, OneOpenPixelInTheRectangleShowsTheSphere) {
  const ts::Camera c = camera();
  std::vector<float> raw(std::size_t(kW) * kH, raw_depth(c, 50));
  const ts::SphereOnScreen s = ts::sphere_on_screen(c, kW, kH, {10, 90, 5}, 4);
  ASSERT_FALSE(s.rect.empty());
  ASSERT_TRUE(ts::DepthOcclusion(raw, kW, kH, c).hidden(s));
  // A hole on each corner of the rectangle in turn: seen. Just outside: still hidden.
  for (const auto& [x, y] : {std::pair{s.rect.x0, s.rect.y0}, std::pair{s.rect.x1, s.rect.y0},
                             std::pair{s.rect.x0, s.rect.y1}, std::pair{s.rect.x1, s.rect.y1}}) {
    std::vector<float> holed = raw;
    holed[std::size_t(y) * kW + x] = 0;
    EXPECT_FALSE(ts::DepthOcclusion(holed, kW, kH, c).hidden(s)) << x << "," << y;
  }
  for (const auto& [x, y] :
       {std::pair{s.rect.x0 - 1, s.rect.y0}, std::pair{s.rect.x1 + 1, s.rect.y1},
        std::pair{s.rect.x0, s.rect.y0 - 1}, std::pair{s.rect.x1, s.rect.y1 + 1}}) {
    std::vector<float> holed = raw;
    holed[std::size_t(y) * kW + x] = 0;
    EXPECT_TRUE(ts::DepthOcclusion(holed, kW, kH, c).hidden(s)) << x << "," << y;
  }
}

TEST(DepthOcclusion, ThePyramidAnswersAsEveryPixelWould) {
  const ts::Camera c = camera();
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  int hidden = 0, shown = 0;
  for (int trial = 0; trial < 20; ++trial) {
    // A ridge line across the image (rows under it at 30-70 m), sky above,
    // with a few notches: what a terrain's horizon looks like.
    std::vector<float> raw(std::size_t(kW) * kH, 0.0f);
    const double depth = 30 + 40 * u(rng);
    for (int x = 0; x < kW; ++x) {
      const int top = int(kH * (0.4 + 0.3 * u(rng) * (x % 7 == 0)));
      for (int y = 0; y < top; ++y) raw[std::size_t(y) * kW + x] = raw_depth(c, depth + y * 0.1);
    }
    const ts::DepthOcclusion occ(raw, kW, kH, c);
    for (int k = 0; k < 200; ++k) {
      const glm::dvec3 centre(80 * (u(rng) - 0.5), 10 + 150 * u(rng), 40 * (u(rng) - 0.5));
      const ts::SphereOnScreen s = ts::sphere_on_screen(c, kW, kH, centre, 0.2 + 6 * u(rng));
      const bool expected = hidden_brute(c, raw, s);
      ASSERT_EQ(occ.hidden(s), expected) << trial << " " << k;
      (expected ? hidden : shown) += 1;
    }
  }
  EXPECT_GT(hidden, 100);
  EXPECT_GT(shown, 100);
}

}  // namespace
