// SPDX-License-Identifier: MIT
#include "terrasprite/experiment/flythrough.h"

#include "terrasprite/experiment/experiment.h"

namespace terrasprite {

void fly(Renderer& renderer, std::span<const Camera> path, ReadBack what,
         const std::function<void(int, const Frame&)>& on_frame,
         const std::function<void(const FrameStats&)>& on_stats,
         const std::function<void(int, int)>& progress) {
  Experiment experiment;
  experiment.add({.renderer = &renderer, .name = "renderer", .read = what});
  ExperimentOptions o;
  o.warmup_draws = 0;
  o.keep_frames = false;
  if (on_frame) o.on_frame = [&](int i, const std::string&, const Frame& f) { on_frame(i, f); };
  if (on_stats)
    o.on_result = [&](const std::string&, const FrameResult& f) {
      on_stats({f.frame, f.cls, f.ms, f.gpu_ms, f.triangles});
    };
  o.progress = progress;
  PathSource cameras(std::vector<Camera>(path.begin(), path.end()));
  experiment.run(cameras, o);
}

std::vector<FrameStats> fly(Renderer& renderer, std::span<const Camera> path, ReadBack what,
                            const std::function<void(int, const Frame&)>& on_frame,
                            const std::function<void(int, int)>& progress) {
  std::vector<FrameStats> stats;
  stats.reserve(path.size());
  fly(
      renderer, path, what, on_frame, [&](const FrameStats& s) { stats.push_back(s); }, progress);
  return stats;
}

}  // namespace terrasprite
