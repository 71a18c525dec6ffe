// SPDX-License-Identifier: MIT
// Orthographic captures of a model's full mesh for its impostors: unlit
// albedo (alpha = coverage) and normal + depth, into the bound framebuffer.
#pragma once
#include <glm/glm.hpp>

#include "objects/gl_model_impl.h"

namespace terrasprite::objects {

/// Saves the framebuffer binding, viewport, clear values, depth and clip
/// state on construction and restores them on destruction.
class GlStateGuard {
 public:
  GlStateGuard();
  ~GlStateGuard();
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

 private:
  GLint fbo_ = 0, viewport_[4] = {0, 0, 0, 0}, depth_func_ = GL_LESS, origin_ = GL_LOWER_LEFT,
        depth_mode_ = GL_NEGATIVE_ONE_TO_ONE, program_ = 0, vao_ = 0;
  GLfloat clear_color_[4] = {0, 0, 0, 0};
  GLfloat clear_depth_ = 1.f;
  GLboolean depth_test_ = GL_FALSE, depth_mask_ = GL_TRUE;
};

/// Draws LOD level `level` of `m` with `local_to_clip` (an orthographic map whose clip
/// z is the depth in [0, 1], w = 1) into the bound framebuffer's attachments
/// 0 (albedo) and 1 (normal, depth), depth-tested nearest-first. The caller
/// sets the viewport and clears. `pack_normal` is for RGBA8 attachments: the
/// normal octahedron-encoded in r, g and the depth in 16 bits over b (high
/// byte) and a (low byte); decode with kPackedGeometryGlsl. Otherwise the
/// attachment gets (normal, depth) as floats.
void capture_view(GlModel::Impl& m, const glm::mat4& local_to_clip, bool pack_normal,
                  int level = 0);

/// GLSL: float packed_depth(vec4 g) and vec3 packed_normal(vec4 g), the
/// inverse of capture_view's packing (depth 1 = nothing recorded).
extern const char* const kPackedGeometryGlsl;

/// Rows of an affine map: clip = (dot(r0, p) + r0.w, ...).
glm::mat4 from_rows(glm::vec4 r0, glm::vec4 r1, glm::vec4 r2);

}  // namespace terrasprite::objects
