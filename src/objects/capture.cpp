// SPDX-License-Identifier: MIT
#include "objects/capture.h"

#include <glm/gtc/type_ptr.hpp>

namespace terrasprite::objects {
namespace {

const char* kCaptureVertex = R"(
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_capture;
out vec3 v_normal;
out vec2 v_uv;
out float v_depth;
void main() {
  vec4 c = u_capture * vec4(a_pos, 1.0);
  v_depth = c.z;
  v_normal = a_normal;
  v_uv = a_uv;
  gl_Position = c;
}
)";

const char* kCaptureFragment = R"(#version 450 core
in vec3 v_normal;
in vec2 v_uv;
in float v_depth;
uniform vec4 u_color;
uniform int u_textured;
uniform sampler2D u_texture;
uniform int u_mirrored;
uniform int u_pack_normal;
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_geometry;
void main() {
  vec4 c = u_color;
  if (u_textured != 0) c *= texture(u_texture, v_uv);
  if (c.a < 0.5) discard;
  // Same rule as the mesh shader: the normal of the side seen.
  bool front = gl_FrontFacing != (u_mirrored != 0);
  vec3 n = normalize(front ? v_normal : -v_normal);
  o_albedo = vec4(c.rgb, 1.0);
  if (u_pack_normal != 0) {
    // 8-bit channels: the normal octahedron-encoded in r, g; depth in 16 bits over b, a.
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    float d16 = floor(clamp(v_depth, 0.0, 1.0) * 65535.0 + 0.5);
    float hi = floor(d16 / 256.0);
    o_geometry = vec4(e * 0.5 + 0.5, hi / 255.0, (d16 - hi * 256.0) / 255.0);
  } else {
    o_geometry = vec4(n, v_depth);
  }
}
)";

}  // namespace

const char* const kPackedGeometryGlsl = R"(
float packed_depth(vec4 g) {
  return (round(g.b * 255.0) * 256.0 + round(g.a * 255.0)) / 65535.0;
}
vec3 packed_normal(vec4 g) {
  vec2 e = g.rg * 2.0 - 1.0;
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}
)";

gl::Program make_capture_program() {
  return gl::link_program(std::string("#version 450 core\n") + kObjectGlsl + kCaptureVertex,
                          kCaptureFragment);
}

GlStateGuard::GlStateGuard() {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
  glGetIntegerv(GL_CLIP_ORIGIN, &origin_);
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &depth_mode_);
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clear_color_);
  glGetFloatv(GL_DEPTH_CLEAR_VALUE, &clear_depth_);
  depth_test_ = glIsEnabled(GL_DEPTH_TEST);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
}

GlStateGuard::~GlStateGuard() {
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(fbo_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glDepthFunc(GLenum(depth_func_));
  glClipControl(GLenum(origin_), GLenum(depth_mode_));
  glUseProgram(GLuint(program_));
  glBindVertexArray(GLuint(vao_));
  glClearColor(clear_color_[0], clear_color_[1], clear_color_[2], clear_color_[3]);
  glClearDepth(clear_depth_);
  if (depth_test_)
    glEnable(GL_DEPTH_TEST);
  else
    glDisable(GL_DEPTH_TEST);
  glDepthMask(depth_mask_);
}

glm::mat4 from_rows(glm::vec4 r0, glm::vec4 r1, glm::vec4 r2) {
  glm::mat4 m(0.f);
  for (int c = 0; c < 4; ++c) {
    m[c][0] = r0[c];
    m[c][1] = r1[c];
    m[c][2] = r2[c];
  }
  m[3][3] = 1.f;
  return m;
}

void capture_view(GlModel::Impl& m, const glm::mat4& local_to_clip, bool pack_normal, int level) {
  const ObjectInstance identity;
  m.upload_instances(std::span(&identity, 1), m.levels[level].vao.id());
  const GLuint p = m.capture_program.id();
  glUseProgram(p);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glUniformMatrix4fv(glGetUniformLocation(p, "u_capture"), 1, GL_FALSE,
                     glm::value_ptr(local_to_clip));
  // Depth grows away from the viewer, so an unmirrored view has a negative
  // determinant (as GL's own projections do).
  glUniform1i(glGetUniformLocation(p, "u_mirrored"),
              glm::determinant(glm::mat3(local_to_clip)) > 0 ? 1 : 0);
  glUniform1i(glGetUniformLocation(p, "u_pack_normal"), pack_normal ? 1 : 0);
  m.draw_level_parts(level, p, 1);
}

}  // namespace terrasprite::objects
