// SPDX-License-Identifier: MIT
// A walkthrough scenario's run summarised: frame time against the target,
// quality at the checkpoints, switches, occlusion; the optimal policy's
// selection figures. Also the scenarios' names and setups.
#include <algorithm>
#include <cmath>

#include "hybrid_stages.h"

namespace terrasprite {
namespace {

constexpr std::array<std::pair<WalkScenario, const char*>, 6> kScenarioNames{{
    {WalkScenario::kFull, "full"},
    {WalkScenario::kIbr, "ibr"},
    {WalkScenario::kPm, "pm"},
    {WalkScenario::kMixed, "mixed"},
    {WalkScenario::kMixedOptimal, "mixed-optimal"},
    {WalkScenario::kFullCulled, "full-culled"},
}};

constexpr std::array<std::pair<DiagnosisCondition, const char*>, 3> kConditionNames{{
    {DiagnosisCondition::kScene, "scene"},
    {DiagnosisCondition::kSky, "sky"},
    {DiagnosisCondition::kScene4, "scene4"},
}};

/// Summary of `value` over the frames where it is present (summarize's
/// empty Summary, count 0, when none).
template <class Value>
Summary summarize_frames(const std::vector<HybridFrame>& frames, Value value) {
  std::vector<double> v;
  for (const HybridFrame& f : frames)
    if (const std::optional<double> x = value(f)) v.push_back(*x);
  return summarize(v);
}

/// A selection figure of the frames that carry the selection's figures.
template <class Field>
Summary summarize_selection(const std::vector<HybridFrame>& frames, Field field) {
  return summarize_frames(frames, [&](const HybridFrame& f) -> std::optional<double> {
    if (!f.selection) return std::nullopt;
    return double(field(*f.selection));
  });
}

}  // namespace

const char* walk_scenario_name(WalkScenario s) {
  for (const auto& [id, name] : kScenarioNames)
    if (id == s) return name;
  return "?";
}

std::optional<WalkScenario> parse_walk_scenario(std::string_view name) {
  for (const auto& [id, n] : kScenarioNames)
    if (name == n) return id;
  return std::nullopt;
}

const char* diagnosis_condition_name(DiagnosisCondition c) {
  for (const auto& [id, name] : kConditionNames)
    if (id == c) return name;
  return "?";
}

std::optional<DiagnosisCondition> parse_diagnosis_condition(std::string_view name) {
  for (const auto& [id, n] : kConditionNames)
    if (name == n) return id;
  return std::nullopt;
}

std::vector<WalkScenario> walk_scenarios(bool occlusion_cull) {
  using S = WalkScenario;
  std::vector<S> s = {S::kFull, S::kIbr, S::kPm, S::kMixed, S::kMixedOptimal};
  if (occlusion_cull) s.push_back(S::kFullCulled);
  return s;
}

HybridScenario walk_scenario(WalkScenario s, bool occlusion_cull) {
  using C = HybridScenario::Control;
  using K = ObjectKind;
  const std::string name = walk_scenario_name(s);
  switch (s) {
    case WalkScenario::kFull:
      // The paper's full geometry draws every instance in the frustum.
      return {name, {K::kMesh}, SelectionPolicy::kStatic, true, C::kNone, false};
    case WalkScenario::kFullCulled:
      // The same image as full (the scoring checks it): what culling alone saves.
      return {name, {K::kMesh}, SelectionPolicy::kStatic, true, C::kNone, true};
    case WalkScenario::kIbr:
      return {name, {K::kRelief}, SelectionPolicy::kImpostorOnly, false, C::kNone, occlusion_cull};
    case WalkScenario::kPm:
      return {name, {K::kMesh}, SelectionPolicy::kGreedy, false, C::kBudgetPi, occlusion_cull};
    case WalkScenario::kMixed:
      return {name,       {K::kMesh, K::kRelief}, SelectionPolicy::kPaper, false, C::kQualityStep,
              occlusion_cull};
    case WalkScenario::kMixedOptimal:
      return {name,  {K::kMesh, K::kRelief, K::kOctahedral}, SelectionPolicy::kOptimal,
              false, C::kBudgetPi,                           occlusion_cull};
  }
  return {};
}

const HybridScenarioResult* HybridBenchResult::scenario(WalkScenario s) const {
  for (const HybridScenarioResult& r : scenarios)
    if (r.scenario == s) return &r;
  return nullptr;
}

namespace hybrid_bench {

std::vector<HybridFrame> hybrid_frames(const RendererRun& run,
                                       const std::map<int, HybridFrameStats>& selection) {
  std::vector<HybridFrame> frames;
  frames.reserve(run.frames.size());
  for (const FrameResult& r : run.frames) {
    HybridFrame f{r, std::nullopt, std::nullopt};
    if (const auto it = selection.find(r.frame); it != selection.end()) f.selection = it->second;
    if (r.quality)
      if (const auto it = r.quality->figures.find(kSsimObjects); it != r.quality->figures.end())
        f.ssim_objects = it->second;
    frames.push_back(std::move(f));
  }
  return frames;
}

HybridScenarioResult summarise(WalkScenario scenario, std::vector<HybridFrame> frames,
                               double target_ms, const std::vector<PathCheckpoint>& checkpoints) {
  HybridScenarioResult s;
  s.scenario = scenario;
  s.ms = summarize_frames(frames, [](const HybridFrame& f) { return std::optional(f.drawn.ms); });
  int within = 0;
  for (const HybridFrame& f : frames) within += f.drawn.ms <= 1.1 * target_ms;
  s.within_10pct = frames.empty() ? 0 : double(within) / double(frames.size());
  const Summary q = summarize_frames(frames, [](const HybridFrame& f) -> std::optional<double> {
    if (!f.drawn.quality) return std::nullopt;
    return f.drawn.quality->ssim;
  });
  const Summary qo = summarize_frames(frames, [](const HybridFrame& f) { return f.ssim_objects; });
  s.mean_ssim = q.count ? q.mean : 1.0;
  s.mean_ssim_objects = qo.count ? qo.mean : 1.0;
  const Summary sw = summarize_selection(frames, [](const auto& x) { return x.switches; });
  s.switches_per_frame = sw.count ? sw.mean : 0.0;
  const Summary oc = summarize_selection(frames, [](const auto& x) { return x.occluded; });
  const Summary om = summarize_selection(frames, [](const auto& x) { return x.occlusion_ms; });
  s.occluded_per_frame = oc.count ? oc.mean : 0.0;
  s.occlusion_ms = om.count ? om.mean : 0.0;
  for (const PathCheckpoint& c : checkpoints) {
    HybridCheckpoint hc{c.name, c.frame};
    for (const HybridFrame& f : frames)
      if (f.drawn.frame == c.frame && f.drawn.quality) {
        hc.ssim = f.drawn.quality->ssim;
        hc.psnr = f.drawn.quality->psnr;
        hc.flip = std::max(0.0, f.drawn.quality->flip);
        hc.ssim_objects = f.ssim_objects.value_or(1.0);
      }
    s.checkpoints.push_back(hc);
  }
  s.frames = std::move(frames);
  return s;
}

SelectionFigures selection_figures(const std::vector<HybridFrame>& frames) {
  SelectionFigures f;
  // Median and p95 of a selection figure over the frames that have it
  // (0 and 0 when none does).
  auto median_p95 = [&](auto field, double& median, double& p95) {
    const Summary s = summarize_selection(frames, field);
    if (s.count == 0) return;
    median = s.median;
    p95 = s.p95;
  };
  median_p95([](const auto& x) { return x.selection_ms; }, f.ms_per_frame, f.ms_p95);
  median_p95([](const auto& x) { return x.policy_ms; }, f.policy_ms_per_frame, f.policy_ms_p95);
  median_p95([](const auto& x) { return x.view_ms; }, f.view_ms_per_frame, f.view_ms_p95);
  double g = 0, o = 0;
  for (const HybridFrame& h : frames) {
    // The optimal policy also prices greedy's choice; -1 where it did not.
    if (!h.selection || h.selection->objective_greedy < 0) continue;
    const double og = h.selection->objective_greedy, oo = h.selection->objective_optimal;
    g += og;
    o += oo;
    const double gain = og > 0 ? (oo - og) / og : 0.0;
    f.gain_mean += gain;
    f.gain_max = std::max(f.gain_max, gain);
    ++f.frames;
  }
  if (f.frames) {
    f.objective_greedy = g / f.frames;
    f.objective_optimal = o / f.frames;
    f.gain_mean /= f.frames;
  }
  return f;
}

}  // namespace hybrid_bench
}  // namespace terrasprite
