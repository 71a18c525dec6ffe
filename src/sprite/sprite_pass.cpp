// SPDX-License-Identifier: MIT
// Projective texture mapping of the keyframe onto the coarse mesh (Chen et
// al. 1999, section 3.1), with the visibility fallback of section 3.3.
#include "sprite/sprite_pass.h"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <utility>

#include "terrasprite/camera/frame.h"

namespace terrasprite {
namespace {

// Keyframe-textured quads: the keyframe's clip coordinates, already biased
// to texture space, divided per fragment by the one projective fetch. No
// drape, no derivatives, no per-quad lookup: llvmpipe keeps its fast path.
const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 a_pos;
uniform mat4 u_vp;
uniform mat4 u_key_vp;  // texture-space bias * keyframe view-projection
out vec3 v_key;
void main() {
  vec4 k = u_key_vp * vec4(a_pos, 1.0);
  v_key = k.xyw;
  gl_Position = u_vp * vec4(a_pos, 1.0);
}
)";

const char* kFragment = R"(#version 450 core
in vec3 v_key;
uniform sampler2D u_key;
out vec4 o_color;
void main() {
  vec4 k = textureProj(u_key, v_key);
  // Keyframe sky (alpha 0) behind a coarse point means the full surface is
  // not there: the coarse mesh sticks out past the true silhouette.
  if (k.a < 0.5) discard;
  o_color = vec4(k.rgb / k.a, 1.0);  // undo the blend with sky at silhouette texels
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
uniform vec4 u_crop;  // the view's part of a keyframe with a margin: uv * zw + xy
out vec4 o_color;
void main() {
  vec2 uv = v_uv * u_crop.zw + u_crop.xy;
  vec4 k = texture(u_key, uv);
  o_color = vec4(k.rgb + (1.0 - k.a) * u_sky, 1.0);
  gl_FragDepth = texture(u_key_depth, uv).r;
}
)";

}  // namespace

SpritePass::SpritePass() : program_(gl::link_program(kVertex, kFragment)) {
  const GLuint p = program_.id();
  u_vp_ = glGetUniformLocation(p, "u_vp");
  u_key_vp_ = glGetUniformLocation(p, "u_key_vp");
  glProgramUniform1i(p, glGetUniformLocation(p, "u_key"), 0);
  composite_ = gl::link_program(kCompositeVertex, kCompositeFragment);
  const GLuint c = composite_.id();
  glProgramUniform1i(c, glGetUniformLocation(c, "u_key"), 0);
  glProgramUniform1i(c, glGetUniformLocation(c, "u_key_depth"), 1);
  u_crop_ = glGetUniformLocation(c, "u_crop");
  glProgramUniform3f(c, glGetUniformLocation(c, "u_sky"), kSkyColor[0] / 255.f,
                     kSkyColor[1] / 255.f, kSkyColor[2] / 255.f);
}

void SpritePass::composite_keyframe(const Keyframe& key) {
  glUseProgram(composite_.id());
  // A keyframe with a margin: the view is its middle, whole margin pixels in.
  const KeyframeFraming& f = key.framing;
  const double mx = f.margin_px(key.view_width), my = f.margin_px(key.view_height);
  const double fx = key.view_width + 2 * mx, fy = key.view_height + 2 * my;
  glUniform4f(u_crop_, float(mx / fx), float(my / fy), float(key.view_width / fx),
              float(key.view_height / fy));
  glBindTextureUnit(0, key.target.color_texture());
  glBindTextureUnit(1, key.target.depth_texture());
  glDepthFunc(GL_ALWAYS);
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_GREATER);
}

void SpritePass::split(const GpuMesh& coarse, const CoarseGrid& grid,
                       std::span<const std::uint8_t> drape) {
  if (source_ != coarse.vertices.id() || grid_ != grid.serial) {
    source_ = coarse.vertices.id();
    grid_ = grid.serial;
    for (GpuMesh* m : {&key_mesh_, &drape_mesh_}) {
      const GLuint vao = m->vao.id();
      glVertexArrayVertexBuffer(vao, 0, source_, 0, 6 * sizeof(float));
      glVertexArrayElementBuffer(vao, m->indices.id());
      for (GLuint a = 0; a < 2; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao, a, 0);
      }
    }
    last_drape_.clear();
  }
  if (std::equal(drape.begin(), drape.end(), last_drape_.begin(), last_drape_.end())) return;
  last_drape_.assign(drape.begin(), drape.end());
  std::vector<std::uint32_t> key, rest;
  key.reserve(grid.triangles.size());
  rest.reserve(grid.triangles.size());
  key_quads_ = 0;
  for (std::size_t q = 0; q < drape.size() && q + 1 < grid.cell_first.size(); ++q) {
    std::vector<std::uint32_t>& to = drape[q] ? rest : key;
    key_quads_ += drape[q] ? 0 : 1;
    to.insert(to.end(), grid.triangles.begin() + grid.cell_first[q],
              grid.triangles.begin() + grid.cell_first[q + 1]);
  }
  for (auto [m, v] : {std::pair{&key_mesh_, &key}, std::pair{&drape_mesh_, &rest}}) {
    glNamedBufferData(m->indices.id(), GLsizeiptr(v->size() * sizeof(std::uint32_t)),
                      v->empty() ? nullptr : v->data(), GL_DYNAMIC_DRAW);
    m->index_count = GLsizei(v->size());
  }
}

void SpritePass::draw(TerrainGpu& scene, const GpuMesh& coarse, const CoarseGrid& grid,
                      const Keyframe& key, const glm::mat4& vp, std::span<const std::uint8_t> drape,
                      bool lighting) {
  split(coarse, grid, drape);
  if (key_mesh_.index_count > 0) {
    // Clip space [-1, 1] to texture space [0, 1], folded into the matrix.
    const glm::mat4 bias(0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1, 0, 0.5f, 0.5f, 0, 1);
    const glm::mat4 key_vp = bias * key.view_projection;
    glUseProgram(program_.id());
    glUniformMatrix4fv(u_vp_, 1, GL_FALSE, glm::value_ptr(vp));
    glUniformMatrix4fv(u_key_vp_, 1, GL_FALSE, glm::value_ptr(key_vp));
    glBindTextureUnit(0, key.target.color_texture());
    glBindVertexArray(key_mesh_.vao.id());
    glDrawElements(GL_TRIANGLES, key_mesh_.index_count, GL_UNSIGNED_INT, nullptr);
  }
  // One trilinear tap: cheaper than the hand filter's up-to-8 taps and as
  // close to the anisotropic reference (docs/results/2026-12-01-lodsprite-drape-filter.md).
  if (drape_mesh_.index_count > 0) scene.draw(drape_mesh_, vp, lighting, DrapeSampling::kTrilinear);
}

SpritePass::~SpritePass() = default;

}  // namespace terrasprite
