// SPDX-License-Identifier: MIT
// A flythrough schedule that renders every K-th frame for real and warps the
// frames between (Cohen-Or et al.'s video-rate scheme), as a Renderer.
#pragma once
#include <memory>
#include <string>

#include "terrasprite/camera/renderer.h"
#include "terrasprite/warp/warp.h"

namespace terrasprite {

struct WarpScheduleOptions {
  int real_every = 4;  ///< K >= 1: frames 0, K, 2K, ... are real; 1 = no warping
  int margin_x = 0;    ///< extra pixels each side the real renderer draws (see with_margin)
  int margin_y = 0;
  WarpOptions warp;
  bool second_reference = true;  ///< depth: fill holes from the previous real frame
};

/// Wraps `real`, which must render (width + 2 margin_x) x (height + 2
/// margin_y) frames and outlive this (its colour and depth are read back for
/// every real frame). Frame i of the calls to draw() (counted from 0) is real
/// when i % real_every == 0: drawn with the margin camera, returned cropped to
/// its central pixels (class of the real renderer, ms = render + crop); the
/// others are warped from the last real frame (class "warp", ms = warp).
/// draw() returns colour and depth on the CPU already (read_back does
/// nothing). Deterministic. Throws InputError for real_every < 1, negative
/// margins, or a real renderer of the wrong size or without depth.
///
/// Memory: this holds the last two real frames (the second is the depth
/// warp's second reference) and the Warper's output buffers. With draw_into()
/// and the caller's frame handed back each time, nothing is allocated once
/// sizes settle: a real frame is drawn into the buffers of the one two real
/// frames back, and a warp's output swaps buffers with the caller's frame.
class WarpScheduler : public Renderer {
 public:
  WarpScheduler(Renderer& real, int width, int height, WarpScheduleOptions options);
  ~WarpScheduler() override;
  Frame draw(const Camera& camera) override;
  void draw_into(const Camera& camera, Frame& target) override;
  void read_back(Frame&, ReadBack) override {}
  std::string name() const override;

 private:
  Renderer& real_;
  int w_, h_;
  WarpScheduleOptions o_;
  long long count_ = 0;
  std::unique_ptr<Frame> last_, previous_;  ///< the last two real frames, with margin
  Warper warper_;                           ///< keeps the depth warp's scratch between frames
};

}  // namespace terrasprite
