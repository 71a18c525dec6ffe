// SPDX-License-Identifier: MIT
#include "gl/render_target.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "terrasprite/camera/frame.h"

namespace terrasprite::gl {

glm::dmat4 projection_reversed_z(const Camera& c) {
  // Swapping near and far in a zero-to-one projection maps near to 1, far to 0.
  return glm::perspectiveRH_ZO(glm::radians(c.fov_y_deg), c.aspect, c.far_m, c.near_m);
}

int max_samples() {
  GLint n = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &n);
  return std::max(1, int(n));
}

RenderTarget::RenderTarget(int width, int height, int samples)
    : width_(width), height_(height), samples_(samples) {
  if (samples < 1 || samples > max_samples())
    throw std::invalid_argument("render target: " + std::to_string(samples) + " samples (1 to " +
                                std::to_string(max_samples()) + " here)");
  glTextureStorage2D(color_.id(), 1, GL_RGBA8, width, height);
  glTextureStorage2D(depth_.id(), 1, GL_DEPTH_COMPONENT32F, width, height);
  for (GLuint t : {color_.id(), depth_.id()}) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, color_.id(), 0);
  glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  if (glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::logic_error("render target framebuffer incomplete");
  if (samples_ > 1) {
    Multisampled& m = ms_.emplace();
    glNamedRenderbufferStorageMultisample(m.color.id(), samples_, GL_RGBA8, width, height);
    glNamedRenderbufferStorageMultisample(m.depth.id(), samples_, GL_DEPTH_COMPONENT32F, width,
                                          height);
    glNamedFramebufferRenderbuffer(m.fbo.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m.color.id());
    glNamedFramebufferRenderbuffer(m.fbo.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.depth.id());
    if (glCheckNamedFramebufferStatus(m.fbo.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::logic_error("multisampled render target framebuffer incomplete");
  }
}

void RenderTarget::resolve() const {
  if (ms_)
    glBlitNamedFramebuffer(ms_->fbo.id(), fbo_.id(), 0, 0, width_, height_, 0, 0, width_, height_,
                           GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
}

void bind_for_drawing(GLuint fbo, int width, int height) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, width, height);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_STENCIL_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void clear_to_sky() {
  glClearColor(kSkyColor[0] / 255.f, kSkyColor[1] / 255.f, kSkyColor[2] / 255.f, 1.f);
  glClearDepth(0.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

namespace {
void bind_for_reading(GLuint fbo) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  if (fbo == 0) {
    glReadBuffer(GL_BACK);
  } else {
    glNamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0);
  }
}

// glReadPixels cannot read a multisampled framebuffer: `fbo`'s resolved copy
// when it is one (held by `copy`, made unless it has the size), else `fbo` itself.
// `mask`: the buffers the caller reads. A depth read resolves no colour: in
// llvmpipe that resolve is a full pass over every sample of the image.
GLuint readable(GLuint fbo, int width, int height, std::optional<RenderTarget>& copy,
                GLbitfield mask) {
  if (fbo == 0) return 0;
  GLint samples = 0;
  glGetNamedFramebufferParameteriv(fbo, GL_SAMPLES, &samples);
  if (samples <= 1) return fbo;
  if (!copy || copy->width() != width || copy->height() != height) copy.emplace(width, height);
  glBlitNamedFramebuffer(fbo, copy->framebuffer(), 0, 0, width, height, 0, 0, width, height, mask,
                         GL_NEAREST);
  return copy->framebuffer();
}
}  // namespace

Image read_color(GLuint fbo, int width, int height) {
  Image img(width, height);
  std::vector<std::uint8_t> raw(img.rgba.size());
  std::optional<RenderTarget> copy;
  bind_for_reading(readable(fbo, width, height, copy, GL_COLOR_BUFFER_BIT));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  for (int y = 0; y < height; ++y)  // GL's first row is the bottom one
    std::memcpy(img.rgba.data() + y * row, raw.data() + (height - 1 - y) * row, row);
  return img;
}

std::vector<float> read_depth_raw(GLuint fbo, int width, int height) {
  std::optional<RenderTarget> copy;
  return read_depth_raw(fbo, width, height, copy);
}

std::vector<float> read_depth_raw(GLuint fbo, int width, int height,
                                  std::optional<RenderTarget>& scratch) {
  std::vector<float> raw(static_cast<std::size_t>(width) * height);
  bind_for_reading(readable(fbo, width, height, scratch, GL_DEPTH_BUFFER_BIT));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, raw.data());
  return raw;
}

std::vector<float> read_depth(GLuint fbo, int width, int height, double near_m, double far_m) {
  const std::vector<float> raw = read_depth_raw(fbo, width, height);
  std::vector<float> out(raw.size());
  // Reversed Z: d = near (far - z) / (z (far - near)) inverted to z = n f / (n + d (f - n)).
  const double nf = near_m * far_m, fn = far_m - near_m;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double d = raw[static_cast<std::size_t>(height - 1 - y) * width + x];
      out[static_cast<std::size_t>(y) * width + x] =
          d <= 0.0 ? std::numeric_limits<float>::infinity() : float(nf / (near_m + d * fn));
    }
  return out;
}

void RenderTarget::bind_and_clear() {
  bind_for_drawing(framebuffer(), width_, height_);
  clear_to_sky();
}

Image RenderTarget::read_color() const {
  resolve();
  return gl::read_color(fbo_.id(), width_, height_);
}

std::vector<float> RenderTarget::read_depth(double near_m, double far_m) const {
  resolve();
  return gl::read_depth(fbo_.id(), width_, height_, near_m, far_m);
}

}  // namespace terrasprite::gl
