// SPDX-License-Identifier: MIT
#include "raster/terrain_gpu.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>

#include "terrasprite/common/error.h"

namespace terrasprite {

const char* const kDrapeUvGlsl = R"(
uniform vec4 u_uv;  // world xy -> drape uv: xy * u_uv.xy + u_uv.zw
vec2 drape_uv(vec2 world_xy) { return world_xy * u_uv.xy + u_uv.zw; }
)";

const char* const kHandFilterGlsl = R"(
// Anisotropic filtering by hand: up to 8 trilinear taps along the footprint's
// major axis (derivatives taken by the caller in uniform control flow; the
// sampler must be trilinear only). llvmpipe's own anisotropic path (any max
// anisotropy > 1) spent 5-12 s on single frames of the paper path.
vec4 drape_hand_filtered(sampler2D s, vec2 uv, vec2 gx, vec2 gy) {
  bool x_major = dot(gx, gx) >= dot(gy, gy);
  vec2 major = x_major ? gx : gy, minor = x_major ? gy : gx;
  float n = clamp(ceil(length(major) / max(length(minor), 1e-20)), 1.0, 8.0);
  vec4 c = vec4(0.0);
  for (float i = 0.0; i < n; i += 1.0)
    c += textureGrad(s, uv + major * ((i + 0.5) / n - 0.5), major / n, minor);
  return c / n;
}
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

// Rich shading (TerrainShading::kRich): what a full-resolution renderer
// pays on every pixel of every frame, and LOD-sprite only on keyframes (and
// on quads drawn from the drape). Soft sun shadows marched through the
// height field, horizon-based ambient occlusion in 8 directions, and
// aerial-perspective haze; 57 height fetches per fragment.
const char* kRichGlsl = R"(
uniform sampler2D u_height;  // R32F, texel (i, j) = sample (i, j), row j = 0 north
uniform vec4 u_hm;           // sample index (i, j) = world xy * u_hm.xy + u_hm.zw
uniform vec2 u_hm_size;      // samples per side
uniform float u_spacing;     // metres between samples
uniform vec3 u_eye;          // camera position, metres
uniform float u_haze_m;      // haze e-folding distance, metres
const vec3 kSun = normalize(vec3(-0.5, 0.5, 0.7071));
float height_at(vec2 xy) {
  return textureLod(u_height, (xy * u_hm.xy + u_hm.zw + 0.5) / u_hm_size, 0.0).r;
}
float soft_shadow(vec3 p) {
  float s = 1.0, t = 2.0 * u_spacing;
  for (int i = 0; i < 24; ++i) {
    vec3 q = p + kSun * t;
    s = min(s, 6.0 * (q.z - height_at(q.xy)) / t);
    t *= 1.3;
  }
  return clamp(s, 0.0, 1.0);
}
float ambient_occlusion(vec3 p) {
  float occlusion = 0.0;
  for (int k = 0; k < 8; ++k) {
    float a = 0.78539816 * (float(k) + 0.5);
    vec2 dir = vec2(cos(a), sin(a));
    float horizon = 0.0, r = u_spacing;
    for (int i = 0; i < 4; ++i) {
      horizon = max(horizon, (height_at(p.xy + dir * r) - p.z) / r);
      r *= 2.5;
    }
    occlusion += horizon * inversesqrt(1.0 + horizon * horizon);  // sine of the horizon angle
  }
  return 1.0 - occlusion / 8.0;
}
vec3 rich_shading(vec3 albedo, vec3 fragment, vec3 n) {
  // Shade the true surface under the fragment: a coarse mesh's fragment may
  // lie below it, and would shadow itself.
  vec3 p = vec3(fragment.xy, height_at(fragment.xy));
  vec3 c = albedo * (0.35 * ambient_occlusion(p) + 0.85 * max(dot(n, kSun), 0.0) * soft_shadow(p));
  vec3 view = normalize(fragment - u_eye);
  vec3 haze = mix(vec3(0.59, 0.73, 0.88), vec3(1.0, 0.95, 0.85), pow(max(dot(view, kSun), 0.0), 8.0));
  return mix(c, haze, 1.0 - exp(-length(fragment - u_eye) / u_haze_m));
}
)";

const char* kFragment = R"(
in vec3 v_world;
in vec3 v_normal;
uniform sampler2D u_drape;
uniform int u_lighting;
out vec4 o_color;
void main() {
  vec2 uv = drape_uv(v_world.xy);
  // Two programs, not a branch: a texture() under a condition costs llvmpipe
  // its per-quad filtering path, several times slower at full resolution.
#if HAND_FILTER
  vec4 c = drape_hand_filtered(u_drape, uv, dFdx(uv), dFdy(uv));
#else
  vec4 c = texture(u_drape, uv);
#endif
#if RICH
  c.rgb = rich_shading(c.rgb, v_world, normalize(v_normal));
#else
  if (u_lighting != 0) {
    const vec3 sun = normalize(vec3(-0.5, 0.5, 0.7071));
    c.rgb *= 0.45 + 0.75 * max(dot(normalize(v_normal), sun), 0.0);
  }
#endif
  o_color = vec4(c.rgb, 1.0);
}
)";

constexpr long long kMaxSinglePartSamples = 4097LL * 4097LL;
constexpr int kPartQuads = 2048;  // tile size of chunked grids
constexpr double kMaxMeshBytes = 4.0 * 1024 * 1024 * 1024;

}  // namespace

void upload_grid_mesh(GpuMesh& g, const GridMesh& cpu) {
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
}

TerrainGpu::TerrainGpu(const Terrain& terrain) : terrain_(terrain) {
  const Image& tex = terrain.texture;
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (tex.width > max_size || tex.height > max_size)
    throw InputError(fmt::format("{}: texture {}x{} exceeds the GL limit of {} pixels per side",
                                 terrain.texture_name, tex.width, tex.height, max_size));
  const GLuint t = drape_.id();
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
  for (int rich : {0, 1})
    for (int hand : {0, 1})
      programs_[rich][hand] = gl::link_program(
          kVertex,
          fmt::format("#version 450 core\n#define HAND_FILTER {}\n#define RICH {}\n", hand, rich) +
              kDrapeUvGlsl + kHandFilterGlsl + (rich ? kRichGlsl : "") + kFragment);
  glCreateSamplers(1, &trilinear_);
  glSamplerParameteri(trilinear_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glSamplerParameteri(trilinear_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(trilinear_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(trilinear_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

TerrainGpu::~TerrainGpu() {
  glDeleteSamplers(1, &trilinear_);
}

glm::vec4 TerrainGpu::uv_transform() const {
  // s = (x + ex/2) / ex, t = (ey/2 - y) / ey; u = r0 + s r2, v = r1 + t r3.
  const Heightfield& h = terrain_.heights;
  const auto& r = terrain_.tex_rect;
  const double ex = std::max(h.extent_x(), 1e-9), ey = std::max(h.extent_y(), 1e-9);
  return glm::vec4(float(r[2] / ex), float(-r[3] / ey), float(r[0] + 0.5 * r[2]),
                   float(r[1] + 0.5 * r[3]));
}

const GpuMesh& TerrainGpu::mesh(int quads) {
  auto it = meshes_.find(quads);
  if (it != meshes_.end()) return it->second;
  const Heightfield& h = terrain_.heights;
  const std::vector<int> xs = grid_indices(h.width, quads), ys = grid_indices(h.height, quads);
  const double bytes = double(xs.size()) * ys.size() * 6 * sizeof(float) +
                       double(xs.size() - 1) * (ys.size() - 1) * 6 * sizeof(std::uint32_t);
  if (bytes > kMaxMeshBytes)
    throw InputError(
        fmt::format("{}: a {}x{}-vertex mesh needs {:.1f} GiB of buffers, more than the 4 GiB "
                    "allowed (use --resample)",
                    h.name, xs.size(), ys.size(), bytes / (1024.0 * 1024 * 1024)));
  GpuMesh& g = meshes_[quads];
  if (static_cast<long long>(xs.size()) * ys.size() <= kMaxSinglePartSamples) {
    upload_grid_mesh(g, build_grid_mesh(h, xs, ys));
    return g;
  }
  // Too large for one resident mesh: tiles of kPartQuads quads sharing borders.
  for (std::size_t y0 = 0; y0 + 1 < ys.size(); y0 += kPartQuads)
    for (std::size_t x0 = 0; x0 + 1 < xs.size(); x0 += kPartQuads) {
      std::size_t x1 = std::min(x0 + kPartQuads, xs.size() - 1),
                  y1 = std::min(y0 + kPartQuads, ys.size() - 1);
      std::vector<int> px(xs.begin() + x0, xs.begin() + x1 + 1),
          py(ys.begin() + y0, ys.begin() + y1 + 1);
      upload_grid_mesh(g.parts.emplace_back(), build_grid_mesh(h, px, py));
      g.triangles += g.parts.back().triangles;
    }
  g.columns = int(xs.size());
  g.rows = int(ys.size());
  return g;
}

void TerrainGpu::set_shading(TerrainShading shading) {
  if (shading == TerrainShading::kRich && !heights_) {
    const Heightfield& h = terrain_.heights;
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (h.width > max_size || h.height > max_size)
      throw InputError(
          fmt::format("{}: rich shading needs the heights as one texture, and {}x{} "
                      "exceeds the GL limit of {} per side",
                      h.name, h.width, h.height, max_size));
    const GLuint t = heights_.emplace(GL_TEXTURE_2D).id();
    glTextureStorage2D(t, 1, GL_R32F, h.width, h.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(t, 0, 0, 0, h.width, h.height, GL_RED, GL_FLOAT, h.heights.data());
    for (GLenum k : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER})
      glTextureParameteri(t, k, GL_LINEAR);
    for (GLenum k : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T})
      glTextureParameteri(t, k, GL_CLAMP_TO_EDGE);
  }
  shading_ = shading;
}

void TerrainGpu::use_program(const glm::mat4& vp, bool lighting, DrapeSampling sampling) {
  const bool rich = shading_ == TerrainShading::kRich;
  const bool hand = sampling == DrapeSampling::kHand;
  const GLuint p = programs_[rich][hand].id();
  glUseProgram(p);
  if (rich) {
    const Heightfield& h = terrain_.heights;
    // Reversed-Z perspective: the eye is the point whose clip position is (0, 0, c, 0).
    const glm::dvec4 e = glm::inverse(glm::dmat4(vp)) * glm::dvec4(0, 0, 1, 0);
    glUniform3f(glGetUniformLocation(p, "u_eye"), float(e.x / e.w), float(e.y / e.w),
                float(e.z / e.w));
    glUniform4f(glGetUniformLocation(p, "u_hm"), float(1 / h.spacing_x), float(-1 / h.spacing_y),
                float(0.5 * (h.width - 1)), float(0.5 * (h.height - 1)));
    glUniform2f(glGetUniformLocation(p, "u_hm_size"), float(h.width), float(h.height));
    glUniform1f(glGetUniformLocation(p, "u_spacing"), float(std::min(h.spacing_x, h.spacing_y)));
    glUniform1f(glGetUniformLocation(p, "u_haze_m"), float(3.0 * h.extent()));
    glUniform1i(glGetUniformLocation(p, "u_height"), 1);
    glBindTextureUnit(1, heights_->id());
  }
  glUniformMatrix4fv(glGetUniformLocation(p, "u_vp"), 1, GL_FALSE, glm::value_ptr(vp));
  glUniform4fv(glGetUniformLocation(p, "u_uv"), 1, glm::value_ptr(uv_transform()));
  glUniform1i(glGetUniformLocation(p, "u_lighting"), lighting ? 1 : 0);
  glUniform1i(glGetUniformLocation(p, "u_drape"), 0);
  glBindTextureUnit(0, drape_.id());
  glBindSampler(0, sampling == DrapeSampling::kHardware ? 0 : trilinear_);
}

void TerrainGpu::draw(const GpuMesh& m, const glm::mat4& vp, bool lighting, DrapeSampling sampling,
                      bool cull_back_faces) {
  use_program(vp, lighting, sampling);
  if (cull_back_faces) {
    glEnable(GL_CULL_FACE);
    glFrontFace(GL_CCW);  // the grid's triangles, seen from above
    glCullFace(GL_BACK);
  }
  if (m.parts.empty()) {
    glBindVertexArray(m.vao.id());
    glDrawElements(GL_TRIANGLES, m.index_count, GL_UNSIGNED_INT, nullptr);
  }
  for (const GpuMesh& part : m.parts) {
    glBindVertexArray(part.vao.id());
    glDrawElements(GL_TRIANGLES, part.index_count, GL_UNSIGNED_INT, nullptr);
  }
  glBindSampler(0, 0);
  glDisable(GL_CULL_FACE);  // what every other pass expects
}

void TerrainGpu::draw_in_pieces(const GpuMesh& m, const glm::mat4& vp, bool lighting, int pieces,
                                const std::function<void()>& between) {
  use_program(vp, lighting, DrapeSampling::kHardware);
  const std::size_t parts = std::max<std::size_t>(m.parts.size(), 1);
  const long long n = static_cast<long long>(parts);
  const long long per_part = std::max<long long>(1, (pieces + n - 1) / n);
  auto draw_part = [&](const GpuMesh& part) {
    glBindVertexArray(part.vao.id());
    const long long triangles = part.index_count / 3;
    const long long step = (triangles + per_part - 1) / per_part;
    for (long long first = 0; first < triangles; first += step) {
      const long long count = std::min(step, triangles - first);
      glDrawElements(GL_TRIANGLES, GLsizei(3 * count), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(std::uintptr_t(3 * first * sizeof(GLuint))));
      between();
    }
  };
  if (m.parts.empty()) draw_part(m);
  for (const GpuMesh& part : m.parts) draw_part(part);
  glBindSampler(0, 0);
}

}  // namespace terrasprite
