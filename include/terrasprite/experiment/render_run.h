// SPDX-License-Identifier: MIT
// One renderer along a path (`render`): every frame handed to the caller
// outside its timed span, its figures packed (about 32 bytes a frame, so a
// long run's memory stays flat), and the process's memory sampled along the
// run (a soak's curve).
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "terrasprite/camera/renderer.h"
#include "terrasprite/common/process_memory.h"

namespace terrasprite {

struct RenderRunOptions {
  int first_frame = 0;               ///< the run's index of path[0] (a frame range's start)
  ReadBack read = ReadBack::kColor;  ///< what each frame is read back with
  int memory_every = 100;            ///< sample RSS every n frames drawn, >= 1
  /// At each sample, hand freed heap pages back first (release_free_heap).
  bool heap_trim = true;
  /// Each frame, after its timed span; `frame` is the run's index.
  std::function<void(int frame, const Frame&)> on_frame;
  std::function<void(int done, int total)> progress;
};

struct RenderFrameRecord {
  int frame = 0;  ///< the run's index
  FrameClass cls = FrameClass::kFull;
  double ms = 0, gpu_ms = -1;
  long long triangles = 0;
};

struct RenderRunResult {
  std::vector<RenderFrameRecord> frames;
  double median_ms = 0;
  /// (frames drawn, RSS MiB) at the start and every memory_every frames,
  /// and the trims' time.
  MemoryCurve memory;
  double peak_rss_mb = 0;  ///< at the end of the run
};

/// Draws every camera of `path` in order with `renderer`.
RenderRunResult run_render(Renderer& renderer, std::span<const Camera> path,
                           const RenderRunOptions& options);

}  // namespace terrasprite
