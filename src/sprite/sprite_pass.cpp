// SPDX-License-Identifier: MIT
// Projective texture mapping of the keyframe onto the coarse mesh (Chen et
// al. 1999, section 3.1), with the visibility fallback of section 3.3.
#include "sprite/sprite_pass.h"

#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "terrasprite/frame.h"

namespace terrasprite {
namespace {

const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_vp;
uniform mat4 u_key_vp;
out vec4 v_key;     // keyframe clip coordinates, divided per fragment
out vec2 v_xy;
out vec3 v_normal;
void main() {
  v_key = u_key_vp * vec4(a_pos, 1.0);
  v_xy = a_pos.xy;
  v_normal = a_normal;
  gl_Position = u_vp * vec4(a_pos, 1.0);
}
)";

const char* kFragment = R"(
in vec4 v_key;
in vec2 v_xy;
in vec3 v_normal;
uniform sampler2D u_key;
uniform sampler2D u_drape;
uniform usampler2D u_flags;
uniform int u_qx;
uniform int u_lighting;
out vec4 o_color;
void main() {
  // Drape derivatives here, in uniform control flow.
  vec2 uv_drape = drape_uv(v_xy);
  vec2 gx = dFdx(uv_drape), gy = dFdy(uv_drape);
  // Two triangles per coarse quad, in row order: the primitive names the quad.
  int q = gl_PrimitiveID >> 1;
  if (texelFetch(u_flags, ivec2(q % u_qx, q / u_qx), 0).r == 0u && v_key.w > 0.0) {
    vec2 uv = v_key.xy / v_key.w * 0.5 + 0.5;
    if (uv == clamp(uv, 0.0, 1.0)) {
      // Keyframe sky (alpha 0) behind a coarse point means the full surface
      // is not there: the coarse mesh sticks out past the true silhouette.
      vec4 k = texture(u_key, uv);
      if (k.a < 0.5) discard;
      o_color = vec4(k.rgb / k.a, 1.0);  // undo the blend with sky at silhouette texels
      return;
    }
  }
  vec4 c = drape_hand_filtered(u_drape, uv_drape, gx, gy);
  if (u_lighting != 0) {
    const vec3 sun = normalize(vec3(-0.5, 0.5, 0.7071));
    c.rgb *= 0.45 + 0.75 * max(dot(normalize(v_normal), sun), 0.0);
  }
  o_color = vec4(c.rgb, 1.0);
}
)";

// A keyframe copied into another target (a window): premultiplied colour
// over the sky, and its depth, so later passes depth-test against it.
const char* kCompositeVertex = R"(#version 450 core
out vec2 v_uv;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);  // one triangle covering the target
  v_uv = p;
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";
const char* kCompositeFragment = R"(#version 450 core
in vec2 v_uv;
uniform sampler2D u_key;
uniform sampler2D u_key_depth;
uniform vec3 u_sky;
out vec4 o_color;
void main() {
  vec4 k = texture(u_key, v_uv);
  o_color = vec4(k.rgb + (1.0 - k.a) * u_sky, 1.0);
  gl_FragDepth = texture(u_key_depth, v_uv).r;
}
)";

}  // namespace

SpritePass::SpritePass()
    : program_(gl::link_program(kVertex, std::string("#version 450 core\n") + kDrapeUvGlsl +
                                             kHandFilterGlsl + kFragment)) {
  const GLuint p = program_.id();
  u_vp_ = glGetUniformLocation(p, "u_vp");
  u_key_vp_ = glGetUniformLocation(p, "u_key_vp");
  u_uv_ = glGetUniformLocation(p, "u_uv");
  u_qx_ = glGetUniformLocation(p, "u_qx");
  u_lighting_ = glGetUniformLocation(p, "u_lighting");
  glProgramUniform1i(p, glGetUniformLocation(p, "u_key"), 0);
  glProgramUniform1i(p, glGetUniformLocation(p, "u_drape"), 1);
  glProgramUniform1i(p, glGetUniformLocation(p, "u_flags"), 2);
  composite_ = gl::link_program(kCompositeVertex, kCompositeFragment);
  const GLuint c = composite_.id();
  glProgramUniform1i(c, glGetUniformLocation(c, "u_key"), 0);
  glProgramUniform1i(c, glGetUniformLocation(c, "u_key_depth"), 1);
  glProgramUniform3f(c, glGetUniformLocation(c, "u_sky"), kSkyColor[0] / 255.f,
                     kSkyColor[1] / 255.f, kSkyColor[2] / 255.f);
}

void SpritePass::composite_keyframe(const Keyframe& key) {
  glUseProgram(composite_.id());
  glBindTextureUnit(0, key.target.color_texture());
  glBindTextureUnit(1, key.target.depth_texture());
  glDepthFunc(GL_ALWAYS);
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_GREATER);
}

void SpritePass::draw(TerrainGpu& scene, const GpuMesh& coarse, int quads_x, const Keyframe& key,
                      const glm::mat4& vp, bool lighting) {
  const GLuint p = program_.id();
  glUseProgram(p);
  glUniformMatrix4fv(u_vp_, 1, GL_FALSE, glm::value_ptr(vp));
  glUniformMatrix4fv(u_key_vp_, 1, GL_FALSE, glm::value_ptr(key.view_projection));
  glUniform4fv(u_uv_, 1, glm::value_ptr(scene.uv_transform()));
  glUniform1i(u_qx_, quads_x);
  glUniform1i(u_lighting_, lighting ? 1 : 0);
  glBindTextureUnit(0, key.target.color_texture());
  glBindTextureUnit(1, scene.drape());
  glBindSampler(1, scene.trilinear_sampler());
  glBindTextureUnit(2, key.flags.id());
  glBindVertexArray(coarse.vao.id());
  glDrawElements(GL_TRIANGLES, coarse.index_count, GL_UNSIGNED_INT, nullptr);
  glBindSampler(1, 0);
}

SpritePass::~SpritePass() = default;

}  // namespace terrasprite
