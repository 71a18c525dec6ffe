// SPDX-License-Identifier: MIT
#include "raster/gl_terrain.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "terrasprite/error.h"

namespace terrasprite {

const char* const kDrapeUvGlsl = R"(
uniform vec4 u_uv;  // world xy -> drape uv: xy * u_uv.xy + u_uv.zw
vec2 drape_uv(vec2 world_xy) { return world_xy * u_uv.xy + u_uv.zw; }
)";

namespace {

const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_vp;
out vec3 v_world;
out vec3 v_normal;
void main() {
  v_world = a_pos;
  v_normal = a_normal;
  gl_Position = u_vp * vec4(a_pos, 1.0);
}
)";

const char* kFragment = R"(
in vec3 v_world;
in vec3 v_normal;
uniform sampler2D u_drape;
uniform int u_lighting;
out vec4 o_color;
void main() {
  vec4 c = texture(u_drape, drape_uv(v_world.xy));
  if (u_lighting != 0) {
    const vec3 sun = normalize(vec3(-0.5, 0.5, 0.7071));
    c.rgb *= 0.45 + 0.75 * max(dot(normalize(v_normal), sun), 0.0);
  }
  o_color = vec4(c.rgb, 1.0);
}
)";

constexpr long long kMaxResidentSamples = 4097LL * 4097LL;

}  // namespace

GlTerrain::GlTerrain(const Terrain& terrain) : impl_(std::make_unique<Impl>()) {
  impl_->terrain = &terrain;
  const Heightfield& h = terrain.heights;
  if (static_cast<long long>(h.width) * h.height > kMaxResidentSamples)
    throw InputError(fmt::format(
        "{}: {}x{} samples exceed the 4097x4097 a resident GL mesh allows (use --resample)", h.name,
        h.width, h.height));
  const Image& tex = terrain.texture;
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (tex.width > max_size || tex.height > max_size)
    throw InputError(fmt::format("{}: texture {}x{} exceeds the GL limit of {} pixels per side",
                                 terrain.texture_name, tex.width, tex.height, max_size));
  const GLuint t = impl_->drape.id();
  const int levels = 1 + int(std::floor(std::log2(std::max(tex.width, tex.height))));
  glTextureStorage2D(t, levels, GL_RGBA8, tex.width, tex.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t, 0, 0, 0, tex.width, tex.height, GL_RGBA, GL_UNSIGNED_BYTE,
                      tex.rgba.data());
  glGenerateTextureMipmap(t);
  // Trilinear + anisotropic: an aliased reference would make every quality figure meaningless.
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic") ||
      epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic")) {
    GLfloat max_aniso = 1.f;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &max_aniso);
    glTextureParameterf(t, GL_TEXTURE_MAX_ANISOTROPY_EXT, std::min(16.f, max_aniso));
  }
  impl_->program =
      gl::link_program(kVertex, std::string("#version 450 core\n") + kDrapeUvGlsl + kFragment);
}

GlTerrain::~GlTerrain() = default;

const Terrain& GlTerrain::terrain() const {
  return *impl_->terrain;
}

glm::vec4 GlTerrain::Impl::uv_transform() const {
  // s = (x + ex/2) / ex, t = (ey/2 - y) / ey; u = r0 + s r2, v = r1 + t r3.
  const Heightfield& h = terrain->heights;
  const auto& r = terrain->tex_rect;
  const double ex = std::max(h.extent_x(), 1e-9), ey = std::max(h.extent_y(), 1e-9);
  return glm::vec4(float(r[2] / ex), float(-r[3] / ey), float(r[0] + 0.5 * r[2]),
                   float(r[1] + 0.5 * r[3]));
}

const GpuMesh& GlTerrain::Impl::mesh(int quads) {
  auto it = meshes.find(quads);
  if (it != meshes.end()) return it->second;
  const Heightfield& h = terrain->heights;
  std::vector<int> xs, ys;
  if (quads <= 0) {
    xs = level_indices(h.width, 0);
    ys = level_indices(h.height, 0);
  } else {
    xs = quad_indices(h.width, quads);
    ys = quad_indices(h.height, quads);
  }
  GridMesh cpu = build_grid_mesh(h, xs, ys);
  GpuMesh& g = meshes[quads];
  glNamedBufferStorage(g.vertices.id(), GLsizeiptr(cpu.vertices.size() * sizeof(float)),
                       cpu.vertices.data(), 0);
  glNamedBufferStorage(g.indices.id(), GLsizeiptr(cpu.indices.size() * sizeof(std::uint32_t)),
                       cpu.indices.data(), 0);
  const GLuint vao = g.vao.id();
  glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, 6 * sizeof(float));
  glVertexArrayElementBuffer(vao, g.indices.id());
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(vao, a);
    glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
    glVertexArrayAttribBinding(vao, a, 0);
  }
  g.index_count = GLsizei(cpu.indices.size());
  g.triangles = cpu.triangles();
  g.columns = cpu.columns;
  g.rows = cpu.rows;
  return g;
}

void GlTerrain::Impl::draw(const GpuMesh& m, const glm::mat4& vp, bool lighting) {
  const GLuint p = program.id();
  glUseProgram(p);
  glUniformMatrix4fv(glGetUniformLocation(p, "u_vp"), 1, GL_FALSE, glm::value_ptr(vp));
  glUniform4fv(glGetUniformLocation(p, "u_uv"), 1, glm::value_ptr(uv_transform()));
  glUniform1i(glGetUniformLocation(p, "u_lighting"), lighting ? 1 : 0);
  glUniform1i(glGetUniformLocation(p, "u_drape"), 0);
  glBindTextureUnit(0, drape.id());
  glBindVertexArray(m.vao.id());
  glDrawElements(GL_TRIANGLES, m.index_count, GL_UNSIGNED_INT, nullptr);
}

}  // namespace terrasprite
