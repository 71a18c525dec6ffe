// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <cmath>

#include "terrasprite/hybrid/expected_quality.h"
#include "terrasprite/hybrid/instance_view.h"
#include "terrasprite/hybrid/representation_selection.h"
#include "terrasprite/hybrid/selection_hysteresis.h"

namespace terrasprite {
namespace {

/// An instance with four LOD levels and two relief resolutions.
InstanceOptions make_instance(int id, double size_px) {
  InstanceOptions inst{id, size_px, size_px * size_px / (640.0 * 480.0), {}};
  for (int level = 0; level < 4; ++level) {
    const long long tris = 8000 >> (2 * level);
    inst.options.push_back({{ObjectKind::kMesh, level, 64, 12},
                            0.002 + tris * 1e-4,
                            1.0 - 0.03 * level,
                            100 - 8.0 * level,
                            tris,
                            level * 0.6});
  }
  inst.options.push_back({{ObjectKind::kRelief, 0, 64, 12}, 0.05, 0.93, 30, 12, 0});
  inst.options.push_back({{ObjectKind::kRelief, 0, 128, 12}, 0.08, 0.96, 33, 12, 0});
  return inst;
}

std::vector<InstanceOptions> scene(int n) {
  std::vector<InstanceOptions> v;
  for (int i = 0; i < n; ++i) v.push_back(make_instance(i, 20.0 + 17.0 * (i % 13)));
  return v;
}

TEST(Selection, ZeroBudgetTakesTheCheapestInfiniteTheBest) {
  const auto instances = scene(30);
  for (SelectionPolicy p : {SelectionPolicy::kGreedy, SelectionPolicy::kOptimal}) {
    const FrameSelection none = select_representations(p, instances, 0.0);
    const FrameSelection all = select_representations(p, instances, INFINITY);
    for (std::size_t i = 0; i < instances.size(); ++i) {
      double min_cost = INFINITY, max_ssim = 0;
      for (const auto& o : instances[i].options) {
        min_cost = std::min(min_cost, o.cost_ms);
        max_ssim = std::max(max_ssim, o.ssim);
      }
      EXPECT_EQ(instances[i].options[std::size_t(none.option[i])].cost_ms, min_cost);
      EXPECT_EQ(instances[i].options[std::size_t(all.option[i])].ssim, max_ssim);
    }
    if (p == SelectionPolicy::kOptimal) {
      EXPECT_GE(all.objective_optimal, all.objective_greedy);
    }
  }
}

TEST(Selection, PolicyShapes) {
  const auto instances = scene(30);
  const FrameSelection st =
      select_representations(SelectionPolicy::kStatic, instances, 0.0, {.static_error_px = 1.0});
  for (std::size_t i = 0; i < instances.size(); ++i)
    EXPECT_EQ(instances[i].options[std::size_t(st.option[i])].rep.level,
              1);  // 0.6 px <= 1 < 1.2 px
  const FrameSelection ibr = select_representations(SelectionPolicy::kImpostorOnly, instances, 0.0);
  for (std::size_t i = 0; i < instances.size(); ++i)
    EXPECT_EQ(instances[i].options[std::size_t(ibr.option[i])].rep.resolution,
              128);  // first reaching 0.95
  PolicyOptions po;
  po.max_impostor_resolution = 64;  // 128 is over the limit: meshes, on the budget left
  const FrameSelection paper = select_representations(SelectionPolicy::kPaper, instances, 3.0, po);
  EXPECT_LE(paper.cost_ms, 3.0);
  for (std::size_t i = 0; i < instances.size(); ++i)
    EXPECT_EQ(instances[i].options[std::size_t(paper.option[i])].rep.kind, ObjectKind::kMesh);
}

TEST(Selection, PaperLowersItsTargetToFitTheBudgetInTheFrame) {
  // At target 0.95 every instance takes relief 128 (0.08 ms: 2.4 ms for 30);
  // a 1.6 ms budget fits relief 64 (0.93, 0.05 ms) once the target is lowered.
  const auto instances = scene(30);
  PolicyOptions po;
  po.fit_budget = false;
  const FrameSelection as_paper =
      select_representations(SelectionPolicy::kPaper, instances, 1.6, po);
  EXPECT_NEAR(as_paper.cost_ms, 2.4, 1e-9);
  po.fit_budget = true;
  const FrameSelection fitted = select_representations(SelectionPolicy::kPaper, instances, 1.6, po);
  EXPECT_LE(fitted.cost_ms, 1.6);
  for (std::size_t i = 0; i < instances.size(); ++i)
    EXPECT_EQ(instances[i].options[std::size_t(fitted.option[i])].rep.resolution, 64);
}

TEST(Selection, InstanceBehindTheCameraIsNotInView) {
  Camera cam;
  cam.position = {0, 0, 2};
  cam.yaw_deg = 0;  // looking north (+y)
  cam.aspect = 4.0 / 3.0;
  const ObjectInstance ahead{{0, 50, 0}, 0, 1}, behind{{0, -50, 0}, 0, 1};
  const InstanceView a = view_instance(cam, 480, ahead, {0, 0, 1}, 1.5);
  const InstanceView b = view_instance(cam, 480, behind, {0, 0, 1}, 1.5);
  ASSERT_TRUE(a.visible);
  EXPECT_FALSE(b.visible);
  // Seen from the south, 1 m above its centre: phi 0, theta just under 90; size by the sphere.
  EXPECT_NEAR(a.phi_deg, 0.0, 1e-6);
  EXPECT_NEAR(a.theta_deg, 90 - std::atan(1 / 50.0) * 180 / M_PI, 1e-6);
  EXPECT_NEAR(a.size_px, 480 * (1.5 / std::sqrt(50.01 * 50.01 - 2.25)) / std::tan(M_PI / 6), 0.5);
  // Heading east (turned a quarter clockwise), the model's +x points south, at
  // the camera: the tables' camera at phi 270 sits on +x.
  const InstanceView c = view_instance(cam, 480, ObjectInstance{{0, 50, 0}, 90, 1}, {0, 0, 1}, 1.5);
  EXPECT_NEAR(c.phi_deg, 270.0, 1e-6);
  // An empty frame costs nothing.
  EXPECT_EQ(select_representations(SelectionPolicy::kOptimal, {}, 10.0).cost_ms, 0.0);
}

// The pixels an instance can cover weigh its quality in the knapsack. A far
// sphere covers its disc; a near one whose centre projects far outside the
// image still fills a side of it. Its pixels were once 0 (a disc around the
// projected centre), so the policy drew it at its coarsest. CI: microseconds.
TEST(Selection, ANearInstanceBesideTheViewStillCoversItsPixels) {
  Camera cam;
  cam.position = {0, 0, 0};
  cam.yaw_deg = 0;  // looking north (+y)
  cam.aspect = 16.0 / 9.0;
  cam.near_m = 0.1;
  const int h = 180;
  const double w = h * cam.aspect, tx = std::tan(M_PI / 6) * cam.aspect;
  // Far ahead: the disc of its on-screen diameter.
  const InstanceView far = view_instance(cam, h, ObjectInstance{{0, 200, 0}, 0, 1}, {0, 0, 0}, 2);
  ASSERT_TRUE(far.visible);
  EXPECT_NEAR(far.pixels, M_PI / 4 * far.size_px * far.size_px, 0.01 * far.pixels);
  // 11 m sphere, centre 12 m to the right and 3 m ahead: its silhouette
  // spans 13.2-138.8 degrees right of the view axis, the image's right part.
  const InstanceView near = view_instance(cam, h, ObjectInstance{{12, 3, 0}, 0, 1}, {0, 0, 0}, 11);
  ASSERT_TRUE(near.visible);
  const double left = std::tan(std::atan2(12.0, 3.0) - std::asin(11 / std::hypot(12.0, 3.0)));
  const double across = w / 2 - left / tx * w / 2;  // from there to the image's right edge
  EXPECT_NEAR(near.pixels, M_PI / 4 * across * h, 1e-6 * near.pixels);
  EXPECT_GT(near.pixels, 0.25 * w * h);
  // The eye inside the sphere: the whole image.
  const InstanceView inside = view_instance(cam, h, ObjectInstance{{1, 1, 0}, 0, 1}, {0, 0, 0}, 5);
  EXPECT_NEAR(inside.pixels, M_PI / 4 * w * h, 1e-6 * inside.pixels);
}

// A mesh partly outside the view costs its part inside (triangles outside
// it never reach setup): on_screen is the part of its bounding ball inside
// the frustum, sampled on 512 points. CI: microseconds.
TEST(Selection, OnScreenIsThePartOfTheBallInsideTheFrustum) {
  Camera cam;
  cam.position = {0, 0, 0};
  cam.yaw_deg = 0;  // looking north (+y)
  cam.aspect = 16.0 / 9.0;
  const int h = 180;
  const double ty = std::tan(M_PI / 6), tx = ty * cam.aspect;
  const double nx = 1 / std::sqrt(1 + tx * tx);
  auto at = [&](double x, double y) {  // a 2 m ball 100 m ahead
    return view_instance(cam, h, ObjectInstance{{x, 100, y}, 0, 1}, {0, 0, 0}, 2);
  };
  EXPECT_DOUBLE_EQ(at(0, 0).on_screen, 1.0);
  EXPECT_NEAR(at(100 * tx, 0).on_screen, 0.5, 0.02);   // centred on the right plane
  EXPECT_NEAR(at(0, -100 * ty).on_screen, 0.5, 0.02);  // on the bottom one
  // On the top-left edge: the wedge between the two planes' inward normals.
  const double cos_normals = tx * ty / std::sqrt((1 + tx * tx) * (1 + ty * ty));
  EXPECT_NEAR(at(-100 * tx, 100 * ty).on_screen, (M_PI - std::acos(cos_normals)) / (2 * M_PI),
              0.02);
  // Its centre 1 m (half its radius) outside the right plane: the cap inside,
  // h^2 (3r - h) / 4r^3 of the ball (0.156) with h = 1.
  const InstanceView out = at(100 * tx + 1 / nx, 0);
  ASSERT_TRUE(out.visible);
  EXPECT_NEAR(out.on_screen, 1.0 * (3 * 2 - 1) / (4 * 8), 0.02);
  // The eye at the centre of a 50 m ball (a forest walked through): the
  // frustum's solid angle over the sphere's.
  const double solid = 4 * std::asin(std::sin(std::atan(tx)) * std::sin(std::atan(ty)));
  EXPECT_NEAR(view_instance(cam, h, ObjectInstance{{0, 0, 0}, 0, 1}, {0, 0, 0}, 50).on_screen,
              solid / (4 * M_PI), 0.02);
}

TEST(Selection, HysteresisHoldsAndCountsSwitches) {
  auto instances = scene(1);
  SelectionHysteresis h({.hold_frames = 5, .min_gain = 0.0});
  FrameSelection s{{0}, instances[0].options[0].cost_ms, 0};
  EXPECT_EQ(h.apply(instances, s, 100), 0);
  // A switch comes through (the first since frame 0 is not too soon? it is: held).
  int switches = 0;
  for (int f = 0; f < 20; ++f) {
    FrameSelection t{{f % 2 ? 1 : 2}, instances[0].options[f % 2 ? 1 : 2].cost_ms, 0};
    switches += h.apply(instances, t, 100);
  }
  EXPECT_LE(switches, 20 / 5 + 1);  // flip-flopping every frame is held to once per 5 frames
  EXPECT_GE(switches, 1);
}

TEST(Selection, HysteresisLetsALargeGainThroughSoonAfterACut) {
  // A sudden cut in the budget sends every instance to its cheapest (mesh
  // level 3, SSIM 0.91); when the budget is back, holding them there would
  // cost 9% of their quality for a whole hold: they go back at once. A small
  // cut (level 1, 0.97: 3%) is held.
  const auto instances = scene(10);
  SelectionHysteresis h({.hold_frames = 8, .min_gain = 0.01, .max_hold_loss = 0.05});
  auto all_at = [&](int option) {
    FrameSelection s;
    for (const InstanceOptions& inst : instances) {
      s.option.push_back(option);
      s.cost_ms += inst.options[std::size_t(option)].cost_ms;
    }
    return s;
  };
  FrameSelection s = all_at(0);
  h.apply(instances, s, INFINITY);
  s = all_at(3);
  EXPECT_EQ(h.apply(instances, s, 0.0), 10);  // the cut: forced
  s = all_at(0);
  EXPECT_EQ(h.apply(instances, s, INFINITY), 10);  // back within the hold: 9% gain
  s = all_at(1);
  EXPECT_EQ(h.apply(instances, s, 0.0), 10);  // another cut, a small one
  s = all_at(0);
  EXPECT_EQ(h.apply(instances, s, INFINITY), 0);  // 3% gain: held
  for (int option : s.option) EXPECT_EQ(option, 1);
}

TEST(ExpectedQuality, InterpolatesBetweenSizesAndViews) {
  RepresentationQuality rep;
  for (int size : {100, 400})
    for (double phi : {0.0, 90.0, 180.0, 270.0})
      rep.samples.push_back({phi, 90, size, 20.0 + phi / 90, size == 100 ? 0.9 : 0.8});
  const QualityInterpolator q(rep);
  EXPECT_NEAR(q.at(0, 90, 100).ssim, 0.9, 1e-12);   // on a sample
  EXPECT_NEAR(q.at(0, 90, 200).ssim, 0.85, 1e-12);  // halfway in log2(size)
  EXPECT_NEAR(q.at(0, 90, 50).ssim, 0.9, 1e-12);    // clamped below the range
  EXPECT_NEAR(q.at(90, 90, 800).psnr, 21.0, 1e-12);
  const double mid = q.at(45, 90, 100).psnr;  // between phi 0 (20 dB) and 90 (21 dB)
  EXPECT_GT(mid, 20.0);
  EXPECT_LT(mid, 21.5);
  EXPECT_EQ(QualityInterpolator(RepresentationQuality{}).at(0, 0, 10).ssim, 1.0);
}

// A sample without a score (NaN, as an older table may hold) is skipped:
// the views around it are priced from their scored neighbours, never NaN,
// which the knapsack cannot order.
TEST(ExpectedQuality, SamplesWithoutAScoreAreSkipped) {
  RepresentationQuality rep;
  for (int size : {4, 8})
    for (double phi : {0.0, 90.0, 180.0, 270.0})
      rep.samples.push_back(
          {phi, 90, size, 30.0, size == 4 && phi == 180.0 ? std::nan("") : 0.8 + size / 100.0});
  const QualityInterpolator q(rep);
  for (double phi = 0; phi < 360; phi += 15)
    for (double size : {3.0, 4.0, 5.5, 8.0}) {
      const double ssim = q.at(phi, 90, size).ssim;
      EXPECT_TRUE(std::isfinite(ssim)) << phi << " " << size;
      EXPECT_GE(ssim, 0.84 - 1e-12);
      EXPECT_LE(ssim, 0.88 + 1e-12);
    }
  EXPECT_NEAR(q.at(180, 90, 4).ssim, 0.84, 1e-12);  // its scored neighbours' value
}

// The sun is fixed in the world, so an instance's heading says which side
// of it is lit: a table measured at several headings is read linearly
// between the two around the instance's, across 360 too. CI cost: microseconds.
TEST(ExpectedQuality, InterpolatesBetweenHeadingsAroundTheCircle) {
  RepresentationQuality rep;
  for (double heading : {0.0, 90.0})
    for (double phi : {0.0, 90.0, 180.0, 270.0})
      rep.samples.push_back(
          {phi, 90, 100, heading == 0 ? 20.0 : 30.0, heading == 0 ? 0.8 : 0.9, heading});
  const QualityInterpolator q(rep);
  EXPECT_NEAR(q.at(0, 90, 100, 0).ssim, 0.8, 1e-12);
  EXPECT_NEAR(q.at(0, 90, 100, 90).ssim, 0.9, 1e-12);
  EXPECT_NEAR(q.at(0, 90, 100, 45).ssim, 0.85, 1e-12);
  EXPECT_NEAR(q.at(0, 90, 100, 45).psnr, 25.0, 1e-12);
  // From 90 on round to 360 (= 0): 225 is halfway, 350 is 260 / 270 of the way.
  EXPECT_NEAR(q.at(0, 90, 100, 225).ssim, 0.85, 1e-12);
  EXPECT_NEAR(q.at(0, 90, 100, 350).ssim, 0.9 - 0.1 * 260 / 270, 1e-12);
  EXPECT_NEAR(q.at(0, 90, 100, -10).ssim, q.at(0, 90, 100, 350).ssim, 1e-12);
  EXPECT_NEAR(q.at(0, 90, 100, 720 + 45).ssim, 0.85, 1e-12);
  // The spread of the samples read: none on a sample, 0.05 halfway between
  // 0.8 and 0.9, (0.9 - 0.8) sqrt(u (1 - u)) elsewhere.
  EXPECT_NEAR(q.at(0, 90, 100, 90).ssim_spread, 0.0, 1e-6);
  EXPECT_NEAR(q.at(0, 90, 100, 45).ssim_spread, 0.05, 1e-9);
  EXPECT_NEAR(q.at(0, 90, 100, 22.5).ssim_spread, 0.1 * std::sqrt(0.25 * 0.75), 1e-9);
  // The weights computed once serve another representation on the same layout.
  RepresentationQuality other = rep;
  for (QualitySample& s : other.samples) s.ssim -= 0.1;
  const QualityInterpolator o(other);
  ASSERT_TRUE(q.same_layout(o));
  EXPECT_NEAR(o.at(q.weights(0, 90, 100, 45)).ssim, 0.75, 1e-12);
  // One heading: the same for every heading (tables measured before headings).
  RepresentationQuality one;
  for (double phi : {0.0, 90.0, 180.0, 270.0}) one.samples.push_back({phi, 90, 100, 20.0, 0.8});
  const QualityInterpolator single(one);
  EXPECT_NEAR(single.at(0, 90, 100, 137).ssim, 0.8, 1e-12);
  EXPECT_FALSE(single.same_layout(q));
  // A heading missing a view (a sample without a score) has views of its
  // own: its nearest views are searched apart (phi 180 stands on its
  // neighbours at heading 90, all 0.9).
  RepresentationQuality gap = rep;
  for (QualitySample& s : gap.samples)
    if (s.heading_deg == 90 && s.phi_deg == 180) s.ssim = std::nan("");
  const QualityInterpolator g(gap);
  EXPECT_NEAR(g.at(180, 90, 100, 90).ssim, 0.9, 1e-12);
  EXPECT_NEAR(g.at(180, 90, 100, 45).ssim, 0.85, 1e-12);
  EXPECT_NEAR(g.at(0, 90, 100, 0).ssim, 0.8, 1e-12);
}

}  // namespace
}  // namespace terrasprite
