// SPDX-License-Identifier: MIT
#include "terrasprite/gl/gl_renderer.h"

#include "gl/frame_timer.h"
#include "gl/render_target.h"

namespace terrasprite {

struct GlRenderer::Base {
  gl::RenderTarget own;
  std::optional<GlTarget> external;
  gl::FrameTimer timer;
};

GlRenderer::GlRenderer(int width, int height, int samples)
    : base_(std::make_unique<Base>(
          Base{gl::RenderTarget(width, height, samples), std::nullopt, {}})) {}

GlRenderer::~GlRenderer() = default;

int GlRenderer::width() const {
  return base_->own.width();
}
int GlRenderer::height() const {
  return base_->own.height();
}

GlTarget GlRenderer::output() const {
  if (base_->external) return *base_->external;
  return {base_->own.framebuffer(), base_->own.width(), base_->own.height()};
}

void GlRenderer::set_output(std::optional<GlTarget> target) {
  base_->external = target;
}

unsigned GlRenderer::color_texture() const {
  base_->own.resolve();
  return base_->own.color_texture();
}

void GlRenderer::begin_output() {
  const GlTarget t = output();
  gl::bind_for_drawing(t.framebuffer, t.width, t.height);
  gl::clear_to_sky();
}

Frame GlRenderer::make_frame(const Camera& camera, const gl::FrameTime& time, FrameClass cls,
                             long long triangles) const {
  Frame f;
  const GlTarget t = output();
  f.width_px = t.width;
  f.height_px = t.height;
  f.ms = time.ms;
  f.gpu_ms = time.gpu_ms;
  f.cls = cls;
  f.triangles = triangles;
  f.camera = camera;
  return f;
}

gl::RenderTarget& GlRenderer::own_target() {
  return base_->own;
}

gl::FrameTimer& GlRenderer::timer() {
  return base_->timer;
}

void GlRenderer::read_framebuffer(unsigned fbo, int w, int h, const Camera& camera, Frame& frame,
                                  ReadBack what) {
  if (has(what, ReadBack::kColor)) frame.color = gl::read_color(fbo, w, h);
  if (has(what, ReadBack::kDepth))
    frame.depth = gl::read_depth(fbo, w, h, camera.near_m, camera.far_m);
}

void GlRenderer::read_back(Frame& frame, ReadBack what) {
  if (base_->external) {
    const GlTarget& t = *base_->external;
    read_framebuffer(t.framebuffer, t.width, t.height, frame.camera, frame, what);
    return;
  }
  // The own target resolves into its own textures: no copy made per read.
  gl::RenderTarget& own = base_->own;
  own.resolve();
  read_framebuffer(own.resolved_framebuffer(), own.width(), own.height(), frame.camera, frame,
                   what);
}

}  // namespace terrasprite
