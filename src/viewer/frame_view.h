// SPDX-License-Identifier: MIT
// Shows a rendered frame in the window: a texture the render worker drew
// (shared between the contexts, nothing read back), or a CPU renderer's
// colour image uploaded into a texture; drawn over the whole framebuffer.
#pragma once
#include <memory>

#include "terrasprite/common/image.h"

namespace terrasprite::viewer {

/// Needs the window's context current for its whole life.
class FrameView {
 public:
  FrameView();
  ~FrameView();
  FrameView(const FrameView&) = delete;
  FrameView& operator=(const FrameView&) = delete;

  /// Shows `texture` (a GL texture name of a sharing context, rows bottom-up
  /// as GL draws them) from now on; it must stay valid while shown.
  void show(unsigned texture);
  /// Uploads `color` (RGBA8, rows top to bottom) and shows it from now on.
  void upload(const Image& color);
  /// Draws what is shown stretched over the framebuffer `width` x `height`
  /// (sky colour before anything was shown).
  void draw(int width, int height) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace terrasprite::viewer
