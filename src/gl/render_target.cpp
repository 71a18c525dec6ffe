// SPDX-License-Identifier: MIT
#include "gl/render_target.h"

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <stdexcept>

#include "terrasprite/renderer.h"

namespace terrasprite::gl {

glm::dmat4 projection_reversed_z(const Camera& c) {
  // Swapping near and far in a zero-to-one projection maps near to 1, far to 0.
  return glm::perspectiveRH_ZO(glm::radians(c.fov_y_deg), c.aspect, c.far_m, c.near_m);
}

RenderTarget::RenderTarget(int width, int height) : width_(width), height_(height) {
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
}

void RenderTarget::bind_and_clear() {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glViewport(0, 0, width_, height_);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glClearColor(kSkyColor[0] / 255.f, kSkyColor[1] / 255.f, kSkyColor[2] / 255.f, 1.f);
  glClearDepth(0.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

Image RenderTarget::read_color() const {
  Image img(width_, height_);
  std::vector<std::uint8_t> raw(img.rgba.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(color_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(raw.size()), raw.data());
  const std::size_t row = static_cast<std::size_t>(width_) * 4;
  for (int y = 0; y < height_; ++y)  // GL's first row is the bottom one
    std::memcpy(img.rgba.data() + y * row, raw.data() + (height_ - 1 - y) * row, row);
  return img;
}

std::vector<float> RenderTarget::read_depth(double near_m, double far_m) const {
  const std::size_t n = static_cast<std::size_t>(width_) * height_;
  std::vector<float> raw(n), out(n);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(depth_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(n * sizeof(float)),
                    raw.data());
  // Reversed Z: d = near (far - z) / (z (far - near)) inverted to z = n f / (n + d (f - n)).
  const double nf = near_m * far_m, fn = far_m - near_m;
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      double d = raw[static_cast<std::size_t>(height_ - 1 - y) * width_ + x];
      out[static_cast<std::size_t>(y) * width_ + x] =
          d <= 0.0 ? std::numeric_limits<float>::infinity() : float(nf / (near_m + d * fn));
    }
  return out;
}

}  // namespace terrasprite::gl
