// SPDX-License-Identifier: MIT
// A simulated display of the LOD-sprite renderer
// with keyframes on a second thread, beside the same display drawn
// synchronously; frame time is the interval between successive presentations.
#pragma once
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/common/image.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite::lodsprite {

/// One simulated display. Paced (a refresh period > 0): a frame is presented
/// at the first refresh slot at or after its draw ends (its own slot when it
/// is ready in time; a later one when it is late), and the next frame starts
/// right after; flat out (period 0): every frame presented as soon as drawn.
struct DisplayRun {
  std::vector<double> frame_ms;  ///< presentation intervals; frame 0: its own draw time
  std::vector<double> draw_ms;   ///< each frame's draw (the renderer's timed span)
  double period_ms = 0;          ///< refresh period; 0 = flat out
  int late_frames = 0;           ///< paced: frames not ready by their slot
  std::vector<double> decision_ms;
  std::vector<double> sprite_ms;   ///< the intervals ending in a frame of class "sprite"
  std::vector<int> landed_frames;  ///< frames that took a landed keyframe (async)
  int keyframes_in_frame = 0;      ///< frames of class "key" (drawn inside the display's frame)
  AsyncKeyframeStats stats;
  double mean_ssim = 0, mean_psnr = 0;  ///< scored frames (async only: replayed, see below)
  // Summaries of frame_ms (nearest-rank p99), and of the sprite frames' intervals.
  double median_ms = 0, p99_ms = 0, max_ms = 0, total_ms = 0;
  double sprite_median_ms = 0, sprite_p99_ms = 0;
  double draw_median_ms = 0, draw_p99_ms = 0;
  double p99_over_median() const { return p99_ms / std::max(median_ms, 1e-9); }
};

struct AsyncComparison {
  DisplayRun sync, async;
  double display_hz = 0;  ///< both displays' refresh rate; 0 = flat out
  double async_lead = 1;  ///< SpriteOptions::async_lead of the async display
  double main_run_mean_ssim = 0, main_run_mean_psnr = 0;  ///< the interleaved synchronous run
  double ssim_change() const { return async.mean_ssim - main_run_mean_ssim; }
  double p99_over_sync_median() const { return async.p99_ms / std::max(sync.median_ms, 1e-9); }
  bool p99_target_met() const { return async.p99_ms <= 2 * async.median_ms; }
  bool ssim_target_met() const { return std::abs(ssim_change()) <= 0.005; }
  /// The same over its sprite frames only (its keyframe frames are the
  /// reference itself, SSIM 1; an async display shows none after the first).
  double main_run_mean_ssim_sprite_frames = 0;
};

/// Flies `path` as a display twice, synchronously and with asynchronous
/// keyframes (`o` otherwise), through the experiment driver with nothing
/// read back, both paced at `display_hz` (0: flat out). The async frames are
/// then scored against `refs` (the full-resolution frames i with
/// i % every == 0) by replaying them: each frame's keyframe camera is
/// recorded, and a synchronous renderer draws the same keyframe and sprite
/// again (the same pixels: same driver and shaders). `gl` must be current.
AsyncComparison run_async_display(const GlContext& gl, Scene& scene, std::span<const Camera> path,
                                  int width, int height, SpriteOptions o,
                                  const std::vector<Image>& refs, int every, double display_hz);

}  // namespace terrasprite::lodsprite
