// SPDX-License-Identifier: MIT
// What the GL renderers share: where they draw, and reading a frame back.
#pragma once
#include <memory>
#include <optional>

#include "terrasprite/camera/renderer.h"

namespace terrasprite {

namespace gl {
class RenderTarget;
class FrameTimer;
struct FrameTime;
}  // namespace gl

/// A framebuffer to draw into: a GL framebuffer name (0 = the current
/// context's default framebuffer, e.g. a GLFW window's back buffer) and its
/// size in pixels. The caller owns it and keeps it alive while it is set.
struct GlTarget {
  unsigned framebuffer = 0;
  int width = 0, height = 0;
};

/// Base of the GL renderers (MeshRenderer, SpriteRenderer). Each owns an
/// off-screen width x height target (RGBA8 colour + 32F reversed-Z depth
/// textures) and draws into it, or into a target the caller sets. Needs a
/// current GL context for its whole life.
class GlRenderer : public Renderer {
 public:
  ~GlRenderer() override;
  int width() const;
  int height() const;
  /// Where draw() renders: the own target unless set_output() gave another.
  GlTarget output() const;
  /// Draws into `target` from the next draw() on (its size may differ from
  /// the renderer's; the projection keeps the camera's aspect); std::nullopt
  /// returns to the own target. Read-back then reads `target`.
  void set_output(std::optional<GlTarget> target);
  /// The own target's colour texture (sky transparent on LOD-sprite keyframes),
  /// resolved first when the target is multisampled.
  unsigned color_texture() const;
  void read_back(Frame& frame, ReadBack what) override;

 protected:
  /// `samples` > 1: the own target is multisampled (gl::RenderTarget).
  GlRenderer(int width, int height, int samples = 1);
  /// Binds the output framebuffer and sets every GL state the renderers rely
  /// on (viewport, zero-to-one clip control, reversed-Z depth test and write,
  /// no blending, culling, scissor or stencil, full colour mask), then clears
  /// to the sky colour and far depth.
  void begin_output();
  /// A frame of this renderer's size drawn with `camera`, timed `time`.
  Frame make_frame(const Camera& camera, const gl::FrameTime& time, FrameClass cls,
                   long long triangles) const;
  gl::RenderTarget& own_target();
  gl::FrameTimer& timer();
  /// Reads `what` of the frame drawn with `camera` from `fbo` (w x h).
  static void read_framebuffer(unsigned fbo, int w, int h, const Camera& camera, Frame& frame,
                               ReadBack what);

 private:
  struct Base;
  std::unique_ptr<Base> base_;
};

}  // namespace terrasprite
