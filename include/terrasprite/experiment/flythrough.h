// SPDX-License-Identifier: MIT
// One renderer along a path, each frame handed on: the experiment driver with
// a single participant, for `render` and the demo.
#pragma once
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/camera/renderer.h"
#include "terrasprite/common/stats.h"

namespace terrasprite {

/// What a run keeps of each frame.
struct FrameStats {
  int frame = 0;
  FrameClass cls = FrameClass::kFull;
  double ms = 0;
  double gpu_ms = -1;
  long long triangles = 0;
};

/// Renders every camera in order, reading back `what` of each. `on_frame`
/// (may be empty) receives each frame after its timed span ends, so writing
/// or scoring it is never timed. `progress` (may be empty) is called with
/// (done, total). No warm-up draw: the first frame pays first-use costs.
std::vector<FrameStats> fly(Renderer& renderer, std::span<const Camera> path, ReadBack what,
                            const std::function<void(int, const Frame&)>& on_frame = {},
                            const std::function<void(int, int)>& progress = {});

/// The same, keeping nothing: each frame's stats go to `on_stats` as soon as
/// the frame is done, so memory stays flat over any number of frames.
void fly(Renderer& renderer, std::span<const Camera> path, ReadBack what,
         const std::function<void(int, const Frame&)>& on_frame,
         const std::function<void(const FrameStats&)>& on_stats,
         const std::function<void(int, int)>& progress);

}  // namespace terrasprite
