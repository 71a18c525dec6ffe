// SPDX-License-Identifier: MIT
// What a viewer run measured: displayed frames and input-to-display latency.
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/experiment/render_mode.h"

namespace terrasprite::viewer {

struct EventLatency {
  double t = 0;  ///< the event's time in the script, seconds
  double latency_ms =
      -1;  ///< injection to the swap of the first frame rendered with it; -1: never shown
};

struct RunStats {
  RenderMode mode = RenderMode::kSprite;
  int width = 0, height = 0;
  int frames = 0;                 ///< swaps showing a newly rendered frame
  std::vector<double> frame_ms;   ///< intervals between swaps showing newly rendered frames
  std::vector<double> render_ms;  ///< the renderer's own Frame::ms per displayed frame
  std::vector<EventLatency> events;
  Camera camera_start, camera_end;     ///< the flight's first and last pose
  std::map<std::string, int> classes;  ///< displayed new frames by class (key, sprite, warp, ...)
  int keyframes_landed = 0;  ///< displayed frames that took a keyframe drawn on another thread
  /// The keyframe worker's wall time for each landed keyframe, ms (sharing the cores).
  std::vector<double> keyframe_ms;
  struct Compared {
    RenderMode mode = RenderMode::kFull;
    double psnr = 0, ssim = 0, flip = 0;
  };
  std::vector<Compared> comparisons;  ///< every "compare" (F3) of the run, in order
};

/// The stats file: mode, size, frames, fps_median, fps_low_1pct (the rate of
/// the 99th-percentile frame time), frames (displayed new frames), frame_ms_p50, frame_ms_p99,
/// render_ms_p50, latency_ms_p95, latency_ms_max, events [{t, latency_ms}], camera_start and
/// camera_end ({position, yaw_deg, pitch_deg}), classes {class: frames}, keyframes_landed,
/// keyframe_ms_p50 and keyframe_ms_max (the worker's time per landed keyframe; 0 without one) and
/// comparisons [{mode, psnr, ssim, flip}] (against full resolution).
nlohmann::json stats_json(const RunStats& s);

}  // namespace terrasprite::viewer
