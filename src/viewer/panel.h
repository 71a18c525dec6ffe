// SPDX-License-Identifier: MIT
// The live panel (ImGui): frame-time graph with keyframes marked, fps,
// triangles, the LOD-sprite error and threshold, the coarse-mesh size, the
// voxel ratio and warp, the mode switch, compare with full resolution, path
// and screenshot buttons; and the F1 key list.
#pragma once
#include <deque>
#include <optional>
#include <string>

#include "terrasprite/camera/camera.h"
#include "viewer/render_worker.h"

namespace terrasprite::viewer {

/// One displayed frame in the graph.
struct GraphSample {
  float ms = 0;      ///< interval since the previous new frame
  bool key = false;  ///< a keyframe (LOD-sprite "key") or a real frame (voxel)
};

/// What the panel shows; filled by the event loop.
struct PanelInfo {
  std::deque<GraphSample> history;  ///< newest last
  double fps = 0;                   ///< over the graph's span
  double render_ms = 0;             ///< the renderer's own time for the last frame
  long long triangles = 0;
  std::string cls, device;
  double error_px = -1;
  std::optional<AsyncKeyframeStats> keyframes;  ///< the keyframe worker's, in sprite mode
  double stale_ms = 0;  ///< age of the frame on screen while the worker is busy
  bool building = false;
  Camera camera;
  double speed_mps = 0, clearance_m = 0;
  bool orbit = false, recording = false, playing = false, captured = true;
  std::string message;  ///< last action's result (screenshot written, ...)
  /// The last "compare" (figures only; the image stays with the loop).
  bool compared = false, comparing = false;
  double psnr = 0, ssim = 0, flip = 0;
  RenderMode compared_mode = RenderMode::kFull;
  bool show_difference = false;  ///< the window shows the difference image
};

struct PanelActions {
  bool screenshot = false, toggle_record = false, play = false;
  bool compare = false, toggle_difference = false;
};

/// Draws the panel (between ImGui::NewFrame and ImGui::Render); edits
/// `settings` in place when the user switches mode or moves a slider.
PanelActions draw_panel(const PanelInfo& info, LiveSettings& settings);
/// Draws the key list.
void draw_help();

}  // namespace terrasprite::viewer
