// SPDX-License-Identifier: MIT
// Post-render warping: a rendered frame (colour, depth, camera) extrapolated
// to a new camera, so frames between real ones cost a fraction of a render.
// Two methods: the paper's 2D polynomial warp (Cohen-Or, Rich, Lerner,
// Shenkar) and a per-pixel 3D reprojection with depth (after Mark, McMillan,
// Bishop, "Post-rendering 3D warping", 1997) with disocclusion holes.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/camera/frame.h"

namespace terrasprite {

enum class WarpMethod {
  kPoly2,  ///< nine control points, a least-squares 2nd-degree polynomial per axis, bilinear
  kDepth,  ///< per-pixel reprojection with the frame's depth, hole mask and hole filling
};

/// "poly2", "depth"; throws InputError naming `text` otherwise.
WarpMethod parse_warp_method(const std::string& text);
const char* to_string(WarpMethod m);

struct WarpOptions {
  WarpMethod method = WarpMethod::kDepth;
  /// Also return, per output pixel, where it was read in the primary
  /// reference (WarpedFrame::source_x/y); costs 8 bytes a pixel.
  bool keep_sources = false;
};

/// A warped frame and what the warp could not see.
struct WarpedFrame {
  /// Colour; depth in metres along the target's view axis (+inf = sky) —
  /// reprojected under `depth`, the real frame's depth at the sampled point
  /// under `poly2`; cls "warp"; camera = the target; ms = the warp's wall time.
  Frame frame;
  /// width * height, 1 where the primary reference did not see the pixel's
  /// surface (a disocclusion, or outside its image), row-major. Such pixels
  /// are filled from the second reference where it sees them, else by
  /// extending the background along the row.
  std::vector<std::uint8_t> holes;
  double hole_fraction = 0.0;  ///< mean of `holes`
  /// With keep_sources: primary-reference pixel coordinates (x right, y down,
  /// pixel centres at +0.5) each output pixel was read from; NaN for holes.
  std::vector<float> source_x, source_y;
};

/// Warps `real` to the camera `target` at `width` x `height` pixels.
///
/// `real` must carry depth (Frame::depth, width*height, +inf for sky) and the
/// camera it was rendered with; it may be any size and field of view (render
/// it with a margin, see with_margin, so the warp rarely reads outside it).
/// `second`, when given, is another reference (the previous real frame, or one
/// rendered at a predicted camera) used only to fill the holes of `real`
/// under `depth`; it must carry depth too. Runs on the calling thread's TBB
/// arena. Throws InputError when a reference lacks depth or sizes are out of
/// range (1..16384).
WarpedFrame warp_frame(const Frame& real, const Camera& target, int width, int height,
                       const WarpOptions& options = {}, const Frame* second = nullptr);

/// warp_frame with buffers kept between calls: the output frame, hole mask
/// and the depth warp's scratch are reused once their sizes settle, so a
/// warp neither allocates nor clears memory (a 1080p depth warp touches ~30
/// MB). Not thread-safe; one Warper per thread of callers.
class Warper {
 public:
  Warper();
  ~Warper();
  Warper(Warper&&) noexcept;
  Warper& operator=(Warper&&) noexcept;
  /// As warp_frame; the result lives in this Warper until the next call (or
  /// take()).
  const WarpedFrame& warp(const Frame& real, const Camera& target, int width, int height,
                          const WarpOptions& options = {}, const Frame* second = nullptr);
  /// Moves the last result out (the next warp allocates again).
  WarpedFrame take();
  /// Swaps the last result's frame with `frame`: the caller gets the warped
  /// frame, and this Warper keeps `frame`'s buffers for the next warp (reused
  /// when their size fits). Handing back the previous output frame each time
  /// keeps a flythrough's warps free of allocation and page faults.
  void exchange(Frame& frame);
  struct Scratch;  ///< the methods' working buffers (src/warp)

 private:
  WarpedFrame result_;
  std::unique_ptr<Scratch> scratch_;
};

/// The camera at the same eye and orientation as `camera` (rendering width x
/// height) whose image has `margin_x` / `margin_y` more pixels on each side
/// at the same pixel density: wider field of view, aspect
/// (width + 2 margin_x) / (height + 2 margin_y). Render the real frame with it
/// at that size; warping it back to `camera` with no motion returns the
/// central width x height pixels exactly.
Camera with_margin(const Camera& camera, int width, int height, int margin_x, int margin_y);

}  // namespace terrasprite
