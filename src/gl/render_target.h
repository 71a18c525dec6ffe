// SPDX-License-Identifier: MIT
// An off-screen framebuffer rendering straight into textures: RGBA8 colour and
// 32-bit float depth with reversed Z (near = 1, far = 0, GL_GREATER), which
// keeps float depth precise across a whole terrain.
#pragma once
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "gl/gl_objects.h"
#include "terrasprite/camera/camera.h"
#include "terrasprite/common/image.h"

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
/// Colour of `fbo` (0 = the default back buffer), top row first. A
/// multisampled `fbo` is resolved first (into a framebuffer made for the
/// read), as are the depth reads below.
Image read_color(GLuint fbo, int width, int height);
/// Depth of `fbo` as stored: reversed Z (near 1, far and nothing drawn 0),
/// bottom row first. Of a multisampled `fbo`, one sample's depth per pixel
/// (GL's resolve of depth picks one).
std::vector<float> read_depth_raw(GLuint fbo, int width, int height);
class RenderTarget;
/// As above, resolving a multisampled `fbo` into `scratch`, which is made (or
/// remade at another size) when needed and kept for the next read: for a
/// read every frame, which should not create GL objects every frame.
std::vector<float> read_depth_raw(GLuint fbo, int width, int height,
                                  std::optional<RenderTarget>& scratch);
/// Linear depth of `fbo` in metres along the view axis (+inf where nothing was
/// drawn) for the camera whose near/far planes drew it.
std::vector<float> read_depth(GLuint fbo, int width, int height, double near_m, double far_m);

/// The most samples a multisampled RenderTarget may have here (GL_MAX_SAMPLES:
/// 4 on llvmpipe). Needs a current context.
int max_samples();

class RenderTarget {
 public:
  /// `samples` > 1 draws multisampled (MSAA), into renderbuffers, resolved
  /// into the colour and depth textures by resolve() and by every read.
  /// `samples` must be 1 to max_samples() (else std::invalid_argument: the
  /// callers check what users give).
  RenderTarget(int width, int height, int samples = 1);
  /// Binds the framebuffer, sets viewport, clip control and depth state, and
  /// clears to the sky colour and far depth.
  void bind_and_clear();
  /// Colour read back top row first (outside any timed span).
  Image read_color() const;
  /// Linear depth in metres along the view axis (+inf where nothing was drawn)
  /// for the camera whose near/far planes drew this image.
  std::vector<float> read_depth(double near_m, double far_m) const;
  /// Copies the samples' average into the textures (a no-op when single-sampled).
  void resolve() const;
  /// The textures hold what was drawn once resolve() has run (always, single-sampled).
  GLuint color_texture() const { return color_.id(); }
  GLuint depth_texture() const { return depth_.id(); }
  /// The framebuffer drawn into (the multisampled one when samples() > 1).
  GLuint framebuffer() const { return ms_ ? ms_->fbo.id() : fbo_.id(); }
  /// The framebuffer of the textures: what was drawn once resolve() has run.
  GLuint resolved_framebuffer() const { return fbo_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }

 private:
  int width_, height_, samples_;
  Texture color_{GL_TEXTURE_2D};
  Texture depth_{GL_TEXTURE_2D};
  Framebuffer fbo_;  ///< the textures
  struct Multisampled {
    Renderbuffer color, depth;
    Framebuffer fbo;
  };
  std::optional<Multisampled> ms_;  ///< when samples_ > 1
};

}  // namespace terrasprite::gl
