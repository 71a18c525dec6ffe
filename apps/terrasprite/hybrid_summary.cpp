// SPDX-License-Identifier: MIT
// A walkthrough scenario's frames as counters, and its run summarised: frame
// time against the target, quality at the checkpoints, switches; the
// optimal policy's figures.
#include <algorithm>

#include "hybrid_bench.h"

namespace terrasprite::cli {

void annotate_frame(const HybridObjects& objects, FrameResult& r) {
  const HybridFrameStats& s = objects.last();
  r.counters = {{"selection_ms", s.selection_ms},
                {"policy_ms", s.policy_ms},
                {"view_ms", s.view_ms},
                {"predicted_ms", s.predicted_ms},
                {"budget_ms", s.budget_ms},
                {"objects_budget_ms", s.objects_budget_ms},
                {"target_quality", s.target_quality},
                {"expected_ssim", s.expected_ssim},
                {"switches", s.switches},
                {"visible", s.visible},
                {"triangles_min", double(s.triangles_min)},
                {"triangles_max", double(s.triangles_max)},
                {"n_mesh", s.instances_by_kind[0]},
                {"n_relief", s.instances_by_kind[1]},
                {"n_octahedral", s.instances_by_kind[2]},
                {"not_drawn", s.not_drawn},
                {"occluded", s.occluded},
                {"occlusion_ms", s.occlusion_ms},
                {"pace", s.pace},
                {"floor_ms", s.floor_ms},
                {"draw_gap_ms", s.draw_gap_ms}};
  if (s.objective_greedy >= 0) {
    r.counters["objective_greedy"] = s.objective_greedy;
    r.counters["objective_optimal"] = s.objective_optimal;
  }
}

HybridScenarioResult summarise(const RendererRun& run, double target_ms,
                               const std::vector<PathCheckpoint>& checkpoints) {
  HybridScenarioResult s;
  s.name = run.name;
  s.frames = run.frames;
  s.ms = run.ms();
  int within = 0;
  for (const FrameResult& f : run.frames) within += f.ms <= 1.1 * target_ms;
  s.within_10pct = run.frames.empty() ? 0 : double(within) / double(run.frames.size());
  const Summary q = run.quality("ssim"), qo = run.quality("ssim_objects");
  s.mean_ssim = q.count ? q.mean : 1.0;
  s.mean_ssim_objects = qo.count ? qo.mean : 1.0;
  const Summary sw = run.counter("switches");
  s.switches_per_frame = sw.count ? sw.mean : 0.0;
  const Summary oc = run.counter("occluded"), om = run.counter("occlusion_ms");
  s.occluded_per_frame = oc.count ? oc.mean : 0.0;
  s.occlusion_ms = om.count ? om.mean : 0.0;
  for (const PathCheckpoint& c : checkpoints) {
    HybridCheckpoint hc{c.name, c.frame};
    for (const FrameResult& f : run.frames)
      if (f.frame == c.frame && f.quality) {
        hc.ssim = f.quality->ssim;
        hc.psnr = f.quality->psnr;
        hc.flip = std::max(0.0, f.quality->flip);
        const auto it = f.quality->figures.find("ssim_objects");
        hc.ssim_objects = it != f.quality->figures.end() ? it->second : 1.0;
      }
    s.checkpoints.push_back(hc);
  }
  return s;
}

SelectionFigures selection_figures(const RendererRun& run) {
  SelectionFigures f;
  // Median and p95 of a per-frame counter over the frames that have it
  // (0 and 0 when none does).
  auto median_p95 = [&](const char* counter, double& median, double& p95) {
    std::vector<double> v;
    for (const FrameResult& r : run.frames)
      if (const auto it = r.counters.find(counter); it != r.counters.end()) v.push_back(it->second);
    if (v.empty()) return;
    const Summary s = summarize(v);
    median = s.median;
    p95 = s.p95;
  };
  median_p95("selection_ms", f.ms_per_frame, f.ms_p95);
  median_p95("policy_ms", f.policy_ms_per_frame, f.policy_ms_p95);
  median_p95("view_ms", f.view_ms_per_frame, f.view_ms_p95);
  double g = 0, o = 0;
  for (const FrameResult& r : run.frames) {
    const auto gi = r.counters.find("objective_greedy");
    if (gi == r.counters.end()) continue;
    const double og = gi->second, oo = r.counters.at("objective_optimal");
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

}  // namespace terrasprite::cli
