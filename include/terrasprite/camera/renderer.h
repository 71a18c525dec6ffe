// SPDX-License-Identifier: MIT
// The interface every renderer implements: draw a camera's view, then, only
// where a later stage needs pixels on the CPU, read the frame back.
#pragma once
#include <string>

#include "terrasprite/camera/camera.h"
#include "terrasprite/camera/frame.h"

namespace terrasprite {

/// Renders camera views at the renderer's fixed size.
///
/// draw() does the technique's work and returns a Frame with its timings,
/// class, triangle count, size and camera; Frame::ms covers only that work
/// with the pipeline drained (DESIGN.md timing rules). read_back() then copies
/// the last drawn frame's colour and/or linear depth into a Frame; it is never
/// timed and a window (the viewer) never calls it. A GL renderer needs a
/// current GL context for both calls and sets every GL state it relies on at
/// the start of draw(), so another pass (a UI) before or after it cannot break it.
class Renderer {
 public:
  virtual ~Renderer() = default;
  virtual Frame draw(const Camera& camera) = 0;
  /// draw() into `target`, a frame the caller owns and hands back draw after
  /// draw: afterwards `target` is what draw() would have returned. Renderers
  /// that fill colour and depth themselves (the CPU ones, the warp schedule)
  /// reuse its buffers when their sizes fit, so a flythrough neither
  /// allocates nor first-touches a frame's memory per frame (a 1080p colour +
  /// depth frame is 16 MB; on a VM each page fault is tens of microseconds).
  /// Default: target = draw(camera).
  virtual void draw_into(const Camera& camera, Frame& target) { target = draw(camera); }
  /// Fills `frame.color` (RGBA8, sky in kSkyColor) and/or `frame.depth`
  /// (metres, +inf = sky) from the last draw(). Undefined before any draw().
  virtual void read_back(Frame& frame, ReadBack what) = 0;
  virtual std::string name() const = 0;

  /// draw() then read_back(what): the whole frame on the CPU.
  Frame render(const Camera& camera, ReadBack what = ReadBack::kColor) {
    Frame f = draw(camera);
    if (what != ReadBack::kNone) read_back(f, what);
    return f;
  }
};

}  // namespace terrasprite
