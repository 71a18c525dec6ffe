// SPDX-License-Identifier: MIT
// The "not drawn" option (HybridOptions::cull_px): small instances may be left
// out to pay for the large ones under a tight budget, never with budget
// enough for all. Selection only, no GL; the file runs in under 1 ms.
#include <gtest/gtest.h>

#include <cmath>

#include "terrasprite/hybrid/representation_selection.h"
#include "terrasprite/hybrid/selection_hysteresis.h"

namespace terrasprite {
namespace {

/// An instance with three LOD levels (the cheapest 0.01 ms) and an octahedral
/// impostor; `cullable` adds not_drawn_option().
InstanceOptions make_instance(int id, double size_px, bool cullable) {
  InstanceOptions inst{id, size_px, size_px * size_px / (320.0 * 180.0), {}};
  inst.options.push_back({{ObjectKind::kMesh, 0, 0, 0}, 0.20, 1.00, 100, 2000, 0});
  inst.options.push_back({{ObjectKind::kMesh, 1, 0, 0}, 0.05, 0.90, 30, 500, 0.5});
  inst.options.push_back({{ObjectKind::kMesh, 2, 0, 0}, 0.01, 0.40, 15, 20, 4});
  inst.options.push_back({{ObjectKind::kOctahedral, 0, 64, 12}, 0.03, 0.85, 28, 2, 0});
  if (cullable) inst.options.push_back(not_drawn_option());
  return inst;
}

/// Two large instances (not cullable) and 40 tiny ones (2 px, cullable).
std::vector<InstanceOptions> walkthrough_like() {
  std::vector<InstanceOptions> v;
  v.push_back(make_instance(0, 80, false));
  v.push_back(make_instance(1, 60, false));
  for (int i = 0; i < 40; ++i) v.push_back(make_instance(2 + i, 2, true));
  return v;
}

const RepresentationOption& chosen(const std::vector<InstanceOptions>& v, const FrameSelection& s,
                                   std::size_t i) {
  return v[i].options[std::size_t(s.option[i])];
}

constexpr SelectionPolicy kBudgeted[] = {SelectionPolicy::kGreedy, SelectionPolicy::kOptimal,
                                         SelectionPolicy::kPaper};

TEST(NotDrawn, OptionIsMarkedAndFree) {
  const RepresentationOption o = not_drawn_option();
  EXPECT_FALSE(is_drawn(o.rep));
  EXPECT_EQ(o.cost_ms, 0.0);
  EXPECT_EQ(o.ssim, 0.0);
  EXPECT_EQ(o.triangles, 0);
  EXPECT_TRUE(is_drawn(Representation{}));
  EXPECT_TRUE(is_drawn(Representation{ObjectKind::kOctahedral, kNotDrawnLevel, 64, 12}));
}

TEST(NotDrawn, UnderTheFloorTheSmallGoAndTheLargeAreUpgraded) {
  // Every instance at its cheapest: 42 x 0.01 = 0.42 ms. A 0.41 ms budget
  // cannot draw them all; leaving the tiny ones out pays for the large ones
  // at full geometry (2 x 0.20 ms).
  const auto v = walkthrough_like();
  for (SelectionPolicy p : kBudgeted) {
    const FrameSelection s = select_representations(p, v, 0.41);
    EXPECT_LE(s.cost_ms, 0.41 + 1e-12) << selection_policy_name(p);
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_TRUE(is_drawn(chosen(v, s, i).rep)) << selection_policy_name(p);
      EXPECT_EQ(chosen(v, s, i).rep.level, 0) << selection_policy_name(p) << " instance " << i;
    }
  }
}

TEST(NotDrawn, WithBudgetEnoughNothingIsLeftOut) {
  const auto v = walkthrough_like();
  for (SelectionPolicy p : kBudgeted)
    for (double budget : {0.5 + 40 * 0.2, double(INFINITY)}) {
      const FrameSelection s = select_representations(p, v, budget);
      for (std::size_t i = 0; i < v.size(); ++i)
        EXPECT_TRUE(is_drawn(chosen(v, s, i).rep)) << selection_policy_name(p) << " " << i;
    }
}

TEST(NotDrawn, ZeroBudgetLeavesOutOnlyTheCullable) {
  const auto v = walkthrough_like();
  for (SelectionPolicy p : kBudgeted) {
    const FrameSelection s = select_representations(p, v, 0.0);
    EXPECT_EQ(chosen(v, s, 0).cost_ms, 0.01) << selection_policy_name(p);
    EXPECT_EQ(chosen(v, s, 1).cost_ms, 0.01) << selection_policy_name(p);
    for (std::size_t i = 2; i < v.size(); ++i)
      EXPECT_FALSE(is_drawn(chosen(v, s, i).rep)) << selection_policy_name(p) << " " << i;
  }
}

TEST(NotDrawn, HysteresisCountsLeavingOutAsASwitch) {
  std::vector<InstanceOptions> v{make_instance(7, 2, true)};
  SelectionHysteresis h({.hold_frames = 0, .min_gain = 0.0});
  FrameSelection drawn{{2}};
  EXPECT_EQ(h.apply(v, drawn, INFINITY), 0);  // first sight
  FrameSelection out{{int(v[0].options.size()) - 1}};
  EXPECT_EQ(h.apply(v, out, 0.0), 1);
  EXPECT_FALSE(is_drawn(v[0].options[std::size_t(out.option[0])].rep));
}

}  // namespace
}  // namespace terrasprite
