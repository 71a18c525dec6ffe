// SPDX-License-Identifier: MIT
// The driver loop: a camera path through one renderer, each frame handed on.
#pragma once
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "terrasprite/camera.h"
#include "terrasprite/renderer.h"

namespace terrasprite {

/// What a run keeps of each frame.
struct FrameStats {
  int frame = 0;
  std::string cls;
  double ms = 0;
  double gpu_ms = -1;
  long long triangles = 0;
};

/// Renders every camera in order. `on_frame` (may be empty) receives each
/// frame after its timed span ends, so writing or scoring it is never timed.
/// `progress` (may be empty) is called with (done, total).
std::vector<FrameStats> fly(Renderer& renderer, std::span<const Camera> path,
                            const std::function<void(int, const Frame&)>& on_frame = {},
                            const std::function<void(int, int)>& progress = {});

/// Median of `values` (0 for none).
double median(std::vector<double> values);

}  // namespace terrasprite
