// SPDX-License-Identifier: MIT
#include "terrasprite/flythrough.h"

#include <algorithm>

namespace terrasprite {

std::vector<FrameStats> fly(Renderer& renderer, std::span<const Camera> path,
                            const std::function<void(int, const Frame&)>& on_frame,
                            const std::function<void(int, int)>& progress) {
  std::vector<FrameStats> stats;
  stats.reserve(path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    Frame f = renderer.render(path[i]);
    stats.push_back({int(i), f.cls, f.ms, f.gpu_ms, f.triangles});
    if (on_frame) on_frame(int(i), f);
    if (progress) progress(int(i) + 1, int(path.size()));
  }
  return stats;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  auto mid = v.begin() + v.size() / 2;
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2) return *mid;
  double hi = *mid;
  double lo = *std::max_element(v.begin(), mid);
  return 0.5 * (lo + hi);
}

}  // namespace terrasprite
