// SPDX-License-Identifier: MIT
#include "terrasprite/flythrough.h"

#include "terrasprite/experiment.h"

namespace terrasprite {

std::vector<FrameStats> fly(Renderer& renderer, std::span<const Camera> path, ReadBack what,
                            const std::function<void(int, const Frame&)>& on_frame,
                            const std::function<void(int, int)>& progress) {
  Experiment experiment;
  experiment.add({.renderer = &renderer, .name = "renderer", .read = what});
  ExperimentOptions o;
  o.warmup_draws = 0;
  if (on_frame) o.on_frame = [&](int i, const std::string&, const Frame& f) { on_frame(i, f); };
  o.progress = progress;
  PathSource cameras(std::vector<Camera>(path.begin(), path.end()));
  const ExperimentResult r = experiment.run(cameras, o);
  std::vector<FrameStats> stats;
  for (const FrameResult& f : r.runs.front().frames)
    stats.push_back({f.frame, f.cls, f.ms, f.gpu_ms, f.triangles});
  return stats;
}

}  // namespace terrasprite
