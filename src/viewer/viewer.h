// SPDX-License-Identifier: MIT
// `terrasprite view`: the interactive flythrough. The event thread polls input
// (or replays a script through the same callbacks), moves the camera, and
// shows the newest frame the render worker finished, with the panel on top.
#pragma once
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/output/output_file.h"
#include "terrasprite/terrain/heightfield.h"
#include "viewer/fly_controller.h"
#include "viewer/input_event.h"
#include "viewer/render_worker.h"
#include "viewer/run_stats.h"

namespace terrasprite::viewer {

struct ViewerOptions {
  int width = 1280, height = 720;  ///< window and render size, pixels
  LiveSettings settings;
  std::vector<ScriptEvent> script;  ///< replayed at their times; the run ends 1 s after the last
  bool scripted = false;            ///< a script was given (even an empty one)
  int frames = 0;                   ///< end after this many displayed frames (0: no limit)
  std::string record;               ///< record the flight into this path file (from the start)
  double record_every_s = 0.5;      ///< keyframe interval of recordings
  std::string play;                 ///< fly this path file from the start
  FlyOptions fly;
  std::string screenshot_dir = ".";  ///< where F2 screenshots go
  /// Which existing files a script's screenshots and the recording may
  /// replace (output_file.h); files this run wrote may always be replaced.
  OutputPolicy output;
  /// GL renderers draw in a context sharing objects with the window's and the
  /// window shows their target's texture, nothing read back. Off (default):
  /// they draw in their own contexts and each frame's colour is read back and
  /// uploaded; on Mesa llvmpipe that is faster (shared, the window's draw
  /// waits for the other context's rendering).
  bool share_context = false;
};

/// Throws InputError unless every file the run is told to write can be
/// written (check_output_file): the recording and each script screenshot;
/// and `screenshot_dir` must be a directory. run_viewer calls it before the
/// window opens.
void check_view_outputs(const ViewerOptions& options);

/// Runs the viewer until the window closes, ESCAPE, the script ends or
/// `frames` frames were shown; returns what it measured. `heights` and the
/// factory's captures must outlive the call. Throws DeviceError without a
/// display or GL, InputError for a bad path file, and what the factory throws.
RunStats run_viewer(const Heightfield& heights, const Camera& start, const ViewerOptions& options,
                    const ViewRendererFactory& factory);

}  // namespace terrasprite::viewer
