// SPDX-License-Identifier: MIT
// Void filling on surfaces whose truth is known: a cone and a ridge with holes
// cut out. The filled surface must be no steeper than the terrain around the
// void (within 1%: no cliffs where two rims meet) and close to the truth:
// RMS under 2% of s R on a flank (slope s, void radius R), under s R / sqrt(6)
// + 10% where a peak or crest is cut off (the error of a flat cap).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/nodata_fill.h"

using namespace terrasprite;

namespace {

constexpr int kN = 129;

struct Holed {
  std::vector<float> truth, filled;
  std::vector<std::uint8_t> hole;  // 1 where cut out
};

// The surface z(x, y) on a kN x kN grid of 1 m cells, a disc of `radius` cells
// around (cx, cy) cut out and filled.
Holed fill_disc(const std::function<double(double, double)>& z, double cx, double cy,
                double radius) {
  Holed r;
  std::vector<std::uint8_t> valid(kN * kN, 1);
  r.hole.assign(kN * kN, 0);
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      r.truth.push_back(float(z(x, y)));
      if (std::hypot(x - cx, y - cy) <= radius) valid[y * kN + x] = 0, r.hole[y * kN + x] = 1;
    }
  r.filled = r.truth;
  for (int p = 0; p < kN * kN; ++p)
    if (r.hole[p]) r.filled[p] = -1e4f;  // what a loader holds in a void: garbage
  EXPECT_GT(fill_nodata(r.filled, valid, kN, kN), 0);
  return r;
}

// Largest slope between 4-neighbours, over the pairs `pick` selects.
double max_slope(const Holed& r, const std::function<bool(int, int)>& pick) {
  double m = 0;
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x)
      for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        const int q = (y + dy) * kN + x + dx, p = y * kN + x;
        if (x + dx < kN && y + dy < kN && pick(p, q))
          m = std::max(m, double(std::abs(r.filled[q] - r.filled[p])));
      }
  return m;
}

double rms_in_hole(const Holed& r) {
  double s = 0;
  int n = 0;
  for (int p = 0; p < kN * kN; ++p)
    if (r.hole[p]) s += std::pow(r.filled[p] - r.truth[p], 2), ++n;
  std::printf("    RMS error in the void: %.4f m over %d cells\n", std::sqrt(s / n), n);
  return std::sqrt(s / n);
}

// Slopes touching the hole vs slopes of the valid terrain within `band` cells of it.
void expect_no_cliffs(const Holed& r, double cx, double cy, double radius, double band) {
  auto near = [&](int p) { return std::hypot(p % kN - cx, p / kN - cy) <= radius + band; };
  const double around =
      max_slope(r, [&](int p, int q) { return !r.hole[p] && !r.hole[q] && near(p) && near(q); });
  const double inside = max_slope(r, [&](int p, int q) { return r.hole[p] || r.hole[q]; });
  // Within 1% (float rounding and the 8-neighbour discretisation).
  EXPECT_LE(inside, around * 1.01) << "around " << around;
  std::printf("    max slope: %.4f inside the void, %.4f around it\n", inside, around);
}

}  // namespace

TEST(NodataFill, ConeWithItsApexCutOut) {
  // Slope 0.5 m per cell; the apex disc (radius R = 20) loses 10 m of peak.
  auto cone = [](double x, double y) { return 1000.0 - 0.5 * std::hypot(x - 64, y - 64); };
  Holed r = fill_disc(cone, 64, 64, 20);
  expect_no_cliffs(r, 64, 64, 20, 5);
  // No fill that is never steeper than its rim can rebuild a peak: it caps it flat. The RMS error
  // of a flat cap over a disc is s R / sqrt(6) = 4.08 m; allow 10% over that.
  EXPECT_LE(rms_in_hole(r), 0.5 * 20 / std::sqrt(6.0) * 1.1);
}

TEST(NodataFill, ConeFlankIsAlmostExact) {
  auto cone = [](double x, double y) { return 1000.0 - 0.5 * std::hypot(x - 64, y - 64); };
  Holed r = fill_disc(cone, 100, 64, 15);
  expect_no_cliffs(r, 100, 64, 15, 5);
  EXPECT_LE(rms_in_hole(r), 0.02 * 0.5 * 15);  // under 2% of s R
}

TEST(NodataFill, RidgeCutAcrossItsCrest) {
  // A ridge along x rising eastwards, flanks of slope 0.6, crest through the hole.
  auto ridge = [](double x, double y) { return 800.0 - 0.6 * std::abs(y - 64) + 0.1 * x; };
  Holed r = fill_disc(ridge, 60, 64, 15);
  expect_no_cliffs(r, 60, 64, 15, 5);
  EXPECT_LE(rms_in_hole(r), 0.6 * 15 / std::sqrt(6.0) * 1.1);
}

TEST(NodataFill, TiltedPlaneHasNoStepWhereRimsMeet) {
  // Rims of very different height on either side of a large void: a
  // rim-propagating fill leaves a cliff where they meet; the plane is harmonic,
  // so the fill must give it back.
  auto plane = [](double x, double y) { return 10.0 * x + 2.0 * y; };
  Holed r = fill_disc(plane, 64, 64, 40);
  expect_no_cliffs(r, 64, 64, 40, 3);
  EXPECT_LE(rms_in_hole(r), 0.05);
}

TEST(NodataFill, TinyGridsAndAllNodata) {
  std::vector<float> h = {5, 0, 0, 0};
  std::vector<std::uint8_t> v = {1, 0, 0, 0};
  EXPECT_EQ(fill_nodata(h, v, 2, 2), 3);
  for (float x : h) EXPECT_NEAR(x, 5.f, 1e-3);
  std::vector<std::uint8_t> none = {0, 0, 0, 0};
  EXPECT_THROW(fill_nodata(h, none, 2, 2), InputError);
}
