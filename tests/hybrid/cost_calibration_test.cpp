// SPDX-License-Identifier: MIT
// fit_draw_costs on draws made up from known costs: a timed draw's overhead
// (the flush at glFinish, once a frame) stays out of every term, the draw
// call is what one more costs inside a frame, an instance its own work.
// No GL; well under 1 ms.
#include "terrasprite/hybrid/cost_calibration.h"

#include <gtest/gtest.h>

#include <vector>

namespace terrasprite {
namespace {

// The made-up costs: a timed draw's flush, a draw call, an instance's
// triangles and covered pixels; level l has 4000 / 2^l triangles.
constexpr double flush = 0.08, call = 0.002, per_triangle = 1e-4, per_pixel = 2e-6;
constexpr double small = 380, large = 45000;  // covered pixels at 22 and 360 px
constexpr int n = 8;                          // the batch

double triangles(int level) {
  return 4000.0 / (1 << level);
}

/// Per mesh level below `levels`: one instance at two sizes; at the small
/// size a batch of n in one call and the same n call by call.
std::vector<CalibrationDraw> singles_and_batches(int levels) {
  std::vector<CalibrationDraw> draws;
  for (int level = 0; level < levels; ++level) {
    const Representation rep{ObjectKind::kMesh, level};
    const double tris = triangles(level);
    auto instance = [&](double px) { return per_triangle * tris + per_pixel * px; };
    draws.push_back({0, rep, 22, tris, small, flush + call + instance(small)});
    draws.push_back({0, rep, 360, tris, large, flush + call + instance(large)});
    draws.push_back({0, rep, 22, tris, small, flush + call + n * instance(small), n});
    draws.push_back({0, rep, 22, tris, small, flush + n * call + n * instance(small), n, n});
  }
  return draws;
}

TEST(CostCalibration, TheFlushIsNeitherADrawCallNorAnInstance) {
  DrawCostModel model;
  fit_draw_costs(model, singles_and_batches(4));
  EXPECT_NEAR(model.terms(ObjectKind::kMesh).per_draw_ms, call, 1e-9);
  for (int level = 0; level < 4; ++level) {
    const double tris = triangles(level);
    for (double px : {0.0, small, large})
      EXPECT_NEAR(model.instance_ms({ObjectKind::kMesh, level}, tris, px, 0),
                  per_triangle * tris + per_pixel * px, 1e-9)
          << "level " << level << ", " << px << " px";
  }
}

TEST(CostCalibration, ASpreadBatchSetsAMeshLevelsConstant) {
  // Levels 0 and 1 also have a batch of 24 spread over the image, where an
  // instance costs 1.5x its triangles alone (tiles not shared); 2 and 3 not.
  const int spread = 24;
  std::vector<CalibrationDraw> draws = singles_and_batches(4);
  for (int level = 0; level < 2; ++level)
    draws.push_back(
        {0,
         {ObjectKind::kMesh, level},
         22,
         triangles(level),
         small,
         flush + call + spread * (1.5 * per_triangle * triangles(level) + per_pixel * small),
         spread,
         1,
         true});
  DrawCostModel model;
  fit_draw_costs(model, draws);
  // The spread batch does not disturb the call or the overhead.
  EXPECT_NEAR(model.terms(ObjectKind::kMesh).per_draw_ms, call, 1e-9);
  for (int level = 0; level < 4; ++level) {
    const double tris = triangles(level);
    const double alone = per_triangle * tris + per_pixel * small;
    const double spread_one = 1.5 * per_triangle * tris + per_pixel * small;
    // (batch - one alone) / (n - 1): the marginal spread instance.
    const double at_small = level < 2 ? (spread * spread_one - alone) / (spread - 1) : alone;
    for (double px : {small, large})
      EXPECT_NEAR(model.instance_ms({ObjectKind::kMesh, level}, tris, px, 0),
                  at_small + per_pixel * (px - small), 1e-9)
          << "level " << level << ", " << px << " px";
  }
}

TEST(CostCalibration, APairFromAboveSetsALevelsCulledFraction) {
  // Level 0 timed from above with its hidden back faces drawn and culled
  // (24 spread instances, one flush each): culled, an instance costs 60%.
  const int spread = 24;
  std::vector<CalibrationDraw> draws = singles_and_batches(2);
  const Representation level0{ObjectKind::kMesh, 0};
  const double drawn = spread * 1.5 * per_triangle * 4000;
  draws.push_back({0, level0, 22, 4000, small, flush + call + drawn, spread, 1, true, true, false});
  draws.push_back(
      {0, level0, 22, 4000, small, flush + call + 0.6 * drawn, spread, 1, true, true, true});
  DrawCostModel model;
  fit_draw_costs(model, draws);
  // The pair is neither a spread batch nor a draw of one: the rest is as before.
  EXPECT_NEAR(model.terms(ObjectKind::kMesh).per_draw_ms, call, 1e-9);
  for (int level = 0; level < 2; ++level) {
    const double tris = triangles(level);
    const Representation rep{ObjectKind::kMesh, level};
    const double alone = per_triangle * tris + per_pixel * large;
    EXPECT_NEAR(model.instance_ms(rep, tris, large, 0), alone, 1e-9);
    // The fraction is the pair's ratio with the flush off (the call, in
    // both, moves it by 1e-4), and only where a level was timed both ways.
    const double fraction = level == 0 ? 0.6 : 1.0;
    EXPECT_NEAR(model.instance_ms(rep, tris, large, 0, true), fraction * alone, 1e-3 * alone)
        << "level " << level;
    FrameLoad load;
    model.add(load, rep, tris, large, 0, true);
    EXPECT_NEAR(model.predict(load), model.instance_ms(rep, tris, large, 0, true), 1e-12);
  }
}

TEST(CostCalibration, AMeshHalfOutsideTheImageCostsItsTrianglesInside) {
  // Its pixels are clipped by the caller; its per-instance (triangle) time
  // scales by the part on screen. An impostor's does not (not measured).
  DrawCostModel model;
  fit_draw_costs(model, singles_and_batches(2));
  const double tris = triangles(0);
  const Representation rep{ObjectKind::kMesh, 0};
  const double whole = model.instance_ms(rep, tris, 0, 0);
  ASSERT_GT(whole, 0);
  EXPECT_NEAR(model.instance_ms(rep, tris, large, 0, false, 0.5),
              0.5 * whole + model.instance_ms(rep, tris, large, 0) - whole, 1e-12);
  EXPECT_NEAR(model.instance_ms(rep, tris, 0, 0, false, -1), 0.0, 1e-12);  // clamped to [0, 1]
  EXPECT_NEAR(model.instance_ms(rep, tris, 0, 0, false, 2), whole, 1e-12);
  FrameLoad load;
  model.add(load, rep, tris, large, 0, false, 0.5);
  EXPECT_NEAR(model.predict(load), model.instance_ms(rep, tris, large, 0, false, 0.5), 1e-12);
  // Uncalibrated (another model's level 5, no "any model" cost): the kind's
  // per-triangle term scales, its per-instance term does not.
  const Representation other{ObjectKind::kMesh, 5};
  ASSERT_FALSE(model.calibrated(other, 3));
  const DrawCostTerms& t = model.terms(ObjectKind::kMesh);
  EXPECT_NEAR(
      model.instance_ms(other, 1000, 0, 3) - model.instance_ms(other, 1000, 0, 3, false, 0.25),
      0.75 * 1000 * t.per_triangle_ms, 1e-12);
  const Representation relief{ObjectKind::kRelief, 0, 64};
  EXPECT_DOUBLE_EQ(model.instance_ms(relief, 12, large, 0, false, 0.25),
                   model.instance_ms(relief, 12, large, 0));
}

}  // namespace
}  // namespace terrasprite
