// SPDX-License-Identifier: MIT
// Shows a rendered Frame in the window: its colour uploaded into a texture and
// drawn over the whole framebuffer. The adapter until renderers draw straight
// into the window's framebuffer (then this upload disappears).
#pragma once
#include <memory>

#include "terrasprite/image.h"

namespace terrasprite::viewer {

/// Needs the window's context current for its whole life.
class FrameView {
 public:
  FrameView();
  ~FrameView();
  FrameView(const FrameView&) = delete;
  FrameView& operator=(const FrameView&) = delete;

  /// Uploads `color` (RGBA8, rows top to bottom); the texture follows its size.
  void upload(const Image& color);
  /// Draws the last upload stretched over the framebuffer `width` x `height`
  /// (sky colour before the first upload).
  void draw(int width, int height) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace terrasprite::viewer
