// SPDX-License-Identifier: MIT
// An off-screen framebuffer rendering straight into textures: RGBA8 colour and
// 32-bit float depth with reversed Z (near = 1, far = 0, GL_GREATER), which
// keeps float depth precise across a whole terrain.
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include "gl/gl_objects.h"
#include "terrasprite/camera.h"
#include "terrasprite/image.h"

namespace terrasprite::gl {

/// Reversed-Z, zero-to-one projection of `camera` (use with glClipControl
/// GL_ZERO_TO_ONE, which every RenderTarget::bind sets).
glm::dmat4 projection_reversed_z(const Camera& camera);
inline glm::dmat4 view_projection_reversed_z(const Camera& c) {
  return projection_reversed_z(c) * c.view();
}

/// Binds `fbo` (0 = the default framebuffer) for drawing at w x h and sets
/// every state the renderers rely on: viewport, zero-to-one clip control,
/// reversed-Z depth test (GL_GREATER) with depth writes, no blending,
/// culling, scissor or stencil test, full colour mask, filled polygons.
void bind_for_drawing(GLuint fbo, int width, int height);
/// Clears the bound framebuffer to the sky colour and far (0) depth.
void clear_to_sky();
/// Colour of `fbo` (0 = the default back buffer), top row first.
Image read_color(GLuint fbo, int width, int height);
/// Depth of `fbo` as stored: reversed Z (near 1, far and nothing drawn 0),
/// bottom row first.
std::vector<float> read_depth_raw(GLuint fbo, int width, int height);
/// Linear depth of `fbo` in metres along the view axis (+inf where nothing was
/// drawn) for the camera whose near/far planes drew it.
std::vector<float> read_depth(GLuint fbo, int width, int height, double near_m, double far_m);

class RenderTarget {
 public:
  RenderTarget(int width, int height);
  /// Binds the framebuffer, sets viewport, clip control and depth state, and
  /// clears to the sky colour and far depth.
  void bind_and_clear();
  /// Colour read back top row first (outside any timed span).
  Image read_color() const;
  /// Linear depth in metres along the view axis (+inf where nothing was drawn)
  /// for the camera whose near/far planes drew this image.
  std::vector<float> read_depth(double near_m, double far_m) const;
  GLuint color_texture() const { return color_.id(); }
  GLuint depth_texture() const { return depth_.id(); }
  GLuint framebuffer() const { return fbo_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  Texture color_{GL_TEXTURE_2D};
  Texture depth_{GL_TEXTURE_2D};
  Framebuffer fbo_;
};

}  // namespace terrasprite::gl
