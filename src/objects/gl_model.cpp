// SPDX-License-Identifier: MIT
// GlModel: the LOD chain in GPU buffers, instanced mesh drawing, and the
// dispatch to the impostors (relief_impostor.cpp, octahedral_impostor.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>

#include "gl/render_target.h"
#include "objects/gl_model_impl.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace objects {

const char* const kObjectGlsl = R"(
layout(location = 3) in vec4 i_pos_heading;
layout(location = 4) in vec4 i_scale;
// Compass heading h (radians, clockwise seen from above) applied to a model vector.
vec3 heading_rotate(vec3 v, float h) {
  float c = cos(h), s = sin(h);
  return vec3(c * v.x + s * v.y, -s * v.x + c * v.y, v.z);
}
vec3 instance_to_world(vec3 p) { return i_pos_heading.xyz + heading_rotate(p * i_scale.x, i_pos_heading.w); }
vec3 world_to_instance(vec3 w) { return heading_rotate(w - i_pos_heading.xyz, -i_pos_heading.w) / i_scale.x; }
)";

// The terrain's sun (raster/gl_terrain.cpp): Lambert + ambient.
const char* const kSunGlsl = R"(
vec3 sun_lit(vec3 albedo, vec3 n) {
  const vec3 sun = normalize(vec3(-0.5, 0.5, 0.7071));
  return albedo * (0.45 + 0.75 * max(dot(normalize(n), sun), 0.0));
}
)";

}  // namespace objects

namespace {

const char* kMeshVertex = R"(
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_vp;
out vec3 v_normal;
out vec2 v_uv;
void main() {
  v_normal = heading_rotate(a_normal, i_pos_heading.w);
  v_uv = a_uv;
  gl_Position = u_vp * vec4(instance_to_world(a_pos), 1.0);
}
)";

// The material's colour, cut-out texels (alpha under 0.5) discarded: what
// every mesh fragment stage starts from.
const char* kMaterialGlsl = R"(
in vec2 v_uv;
uniform vec4 u_color;
uniform int u_textured;
uniform sampler2D u_texture;
out vec4 o_color;
vec4 material_color() {
  vec4 c = u_color;
  if (u_textured != 0) c *= texture(u_texture, v_uv);
  if (c.a < 0.5) discard;
  return c;
}
)";

const char* kMeshFragment = R"(
in vec3 v_normal;
void main() {
  vec4 c = material_color();
  vec3 n = gl_FrontFacing ? v_normal : -v_normal;  // open meshes show their inside
  o_color = vec4(sun_lit(c.rgb, n), 1.0);
}
)";

// back_face_check.cpp: which faces the camera sees, front white, back red.
// A back face coplanar with a front one (a face doubled with the other
// winding) is pushed behind it, whichever was drawn first: it is no opening.
const char* kMarkBackFragment = R"(
void main() {
  material_color();
  o_color = gl_FrontFacing ? vec4(1.0) : vec4(1.0, 0.0, 0.0, 1.0);
  gl_FragDepth = gl_FrontFacing ? gl_FragCoord.z : gl_FragCoord.z * (1.0 - 1e-5);  // reversed Z
}
)";

void upload_level(objects::GpuLevel& g, const LodLevel& lv) {
  std::vector<float> interleaved(lv.positions.size() * 8);
  for (std::size_t i = 0; i < lv.positions.size(); ++i) {
    float* v = &interleaved[i * 8];
    v[0] = lv.positions[i].x, v[1] = lv.positions[i].y, v[2] = lv.positions[i].z;
    v[3] = lv.normals[i].x, v[4] = lv.normals[i].y, v[5] = lv.normals[i].z;
    v[6] = lv.uvs[i].x, v[7] = lv.uvs[i].y;
  }
  glNamedBufferStorage(g.vertices.id(), GLsizeiptr(interleaved.size() * 4), interleaved.data(), 0);
  glNamedBufferStorage(g.indices.id(), GLsizeiptr(lv.indices.size() * 4), lv.indices.data(), 0);
  const GLuint vao = g.vao.id();
  glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, 8 * sizeof(float));
  glVertexArrayElementBuffer(vao, g.indices.id());
  const GLint sizes[3] = {3, 3, 2};
  const GLuint offsets[3] = {0, 3, 6};
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vao, a);
    glVertexArrayAttribFormat(vao, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a] * sizeof(float));
    glVertexArrayAttribBinding(vao, a, 0);
  }
  g.parts = lv.parts;
  g.bytes = interleaved.size() * 4 + lv.indices.size() * 4;
}

gl::Texture upload_texture(const Image& img) {
  gl::Texture t(GL_TEXTURE_2D);
  const int levels = 1 + int(std::floor(std::log2(std::max(img.width, img.height))));
  glTextureStorage2D(t.id(), levels, GL_RGBA8, img.width, img.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE,
                      img.rgba.data());
  glGenerateTextureMipmap(t.id());
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

void check_representation(const Representation& rep, const GlModel::Impl& m) {
  if (rep.kind == ObjectKind::kMesh) {
    if (rep.level < 0 || rep.level >= int(m.levels.size()))
      throw InputError(fmt::format("{}: no LOD level {} (the chain has {})", m.model.name,
                                   rep.level, m.levels.size()));
    return;
  }
  if (rep.resolution < 16 || rep.resolution > 512)
    throw InputError(fmt::format("impostor resolution {} is outside 16..512", rep.resolution));
  if (rep.kind == ObjectKind::kOctahedral && (rep.views < 2 || rep.views > 32))
    throw InputError(fmt::format("octahedral views {} is outside 2..32", rep.views));
}

}  // namespace

gl::Program objects::make_back_face_mark_program() {
  return gl::link_program(std::string("#version 450 core\n") + kObjectGlsl + kMeshVertex,
                          std::string("#version 450 core\n") + kMaterialGlsl + kMarkBackFragment);
}

ObjectKind parse_object_kind(const std::string& text, const char* option) {
  if (text == "pm" || text == "mesh") return ObjectKind::kMesh;
  if (text == "relief") return ObjectKind::kRelief;
  if (text == "octahedral") return ObjectKind::kOctahedral;
  throw InputError(
      fmt::format("{}: '{}' is not a representation (pm, relief, octahedral)", option, text));
}

const char* object_kind_name(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kMesh:
      return "pm";
    case ObjectKind::kRelief:
      return "relief";
    case ObjectKind::kOctahedral:
      return "octahedral";
  }
  return "?";
}

GlModel::GlModel(const Model& model, std::vector<LodLevel> chain, RepresentationCache cache)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.model = model;
  m.chain = std::move(chain);
  m.cache = std::move(cache);
  m.levels.resize(m.chain.size());
  for (std::size_t i = 0; i < m.chain.size(); ++i) {
    upload_level(m.levels[i], m.chain[i]);
    m.attach_instance_attributes(m.levels[i].vao.id());
  }
  for (const Image& img : model.textures) m.textures.push_back(upload_texture(img));
  const std::string head = std::string("#version 450 core\n") + objects::kObjectGlsl;
  m.mesh_program =
      gl::link_program(head + kMeshVertex, std::string("#version 450 core\n") + objects::kSunGlsl +
                                               kMaterialGlsl + kMeshFragment);
  m.capture_program = objects::make_capture_program();
  m.relief_program = objects::make_relief_program();
  m.octahedral_program = objects::make_octahedral_program();
  m.attach_instance_attributes(m.instance_vao.id());
  m.back_faces_hidden_above = m.find_back_faces_hidden_above();
}

GlModel::~GlModel() = default;

const Model& GlModel::model() const {
  return impl_->model;
}
const std::vector<LodLevel>& GlModel::chain() const {
  return impl_->chain;
}
const RepresentationCache& GlModel::cache() const {
  return impl_->cache;
}

void GlModel::Impl::attach_instance_attributes(GLuint vao) {
  for (GLuint a = 3; a < 5; ++a) {
    glEnableVertexArrayAttrib(vao, a);
    glVertexArrayAttribFormat(vao, a, 4, GL_FLOAT, GL_FALSE, (a - 3) * 4 * sizeof(float));
    glVertexArrayAttribBinding(vao, a, 1);
  }
  glVertexArrayBindingDivisor(vao, 1, 1);
}

void GlModel::Impl::upload_instances(std::span<const ObjectInstance> instances) {
  std::vector<objects::GpuInstance> data(instances.size());
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const ObjectInstance& s = instances[i];
    data[i] = {{float(s.position.x), float(s.position.y), float(s.position.z),
                float(glm::radians(s.heading_deg))},
               {float(s.scale), 0.f, 0.f, 0.f}};
  }
  if (!instance_buffer || instance_capacity < data.size()) {
    instance_capacity = std::max<std::size_t>(64, data.size() * 2);
    instance_buffer.emplace();
    uploaded.clear();
    glNamedBufferStorage(instance_buffer->id(),
                         GLsizeiptr(instance_capacity * sizeof(objects::GpuInstance)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
  }
  // Writing a buffer that a queued draw reads makes llvmpipe drain its
  // pipeline: skip the write when the buffer already holds these instances
  // (impostor captures and quality tables draw the same one again and again).
  const std::size_t bytes = data.size() * sizeof(objects::GpuInstance);
  if (uploaded.size() != bytes || std::memcmp(uploaded.data(), data.data(), bytes) != 0) {
    glNamedBufferSubData(instance_buffer->id(), 0, GLsizeiptr(bytes), data.data());
    uploaded.assign(reinterpret_cast<const std::uint8_t*>(data.data()),
                    reinterpret_cast<const std::uint8_t*>(data.data()) + bytes);
  }
}

void GlModel::Impl::bind_instances(GLuint vao) {
  glVertexArrayVertexBuffer(vao, 1, instance_buffer->id(), 0, sizeof(objects::GpuInstance));
}

void GlModel::Impl::upload_instances(std::span<const ObjectInstance> instances, GLuint vao) {
  upload_instances(instances);
  bind_instances(vao);
}

void GlModel::Impl::draw_level_parts(int level, GLuint p, GLsizei count, GLuint first,
                                     bool cull_all) {
  const objects::GpuLevel& g = levels[level];
  glBindVertexArray(g.vao.id());
  for (const MeshPart& part : g.parts) {
    const Material& mat = model.materials[part.material];
    glUniform4fv(glGetUniformLocation(p, "u_color"), 1, glm::value_ptr(mat.base_color));
    glUniform1i(glGetUniformLocation(p, "u_textured"), mat.texture >= 0 ? 1 : 0);
    glUniform1i(glGetUniformLocation(p, "u_texture"), 0);
    if (mat.texture >= 0) glBindTextureUnit(0, textures[mat.texture].id());
    // Back faces of a single-sided material cannot show: they are not
    // rasterised.
    if (mat.double_sided && !cull_all)
      glDisable(GL_CULL_FACE);
    else
      glEnable(GL_CULL_FACE);
    glDrawElementsInstancedBaseInstance(
        GL_TRIANGLES, GLsizei(part.index_count), GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(std::uintptr_t(part.first_index) * 4), count, first);
  }
  glDisable(GL_CULL_FACE);  // what every other pass expects
}

void GlModel::prepare(const Representation& rep) {
  check_representation(rep, *impl_);
  if (rep.kind == ObjectKind::kRelief) impl_->relief_impostor(rep.resolution);
  if (rep.kind == ObjectKind::kOctahedral) impl_->octahedral_impostor(rep.resolution, rep.views);
}

long long GlModel::triangles(const Representation& rep) const {
  check_representation(rep, *impl_);
  switch (rep.kind) {
    case ObjectKind::kMesh:
      return (long long)impl_->chain[rep.level].triangles();
    case ObjectKind::kRelief:
      return 12;
    case ObjectKind::kOctahedral:
      return 2;
  }
  return 0;
}

std::size_t GlModel::bytes(const Representation& rep) {
  check_representation(rep, *impl_);
  switch (rep.kind) {
    case ObjectKind::kMesh:
      return impl_->levels[rep.level].bytes;
    case ObjectKind::kRelief:
      return impl_->relief_impostor(rep.resolution).bytes;
    case ObjectKind::kOctahedral:
      return impl_->octahedral_impostor(rep.resolution, rep.views).bytes;
  }
  return 0;
}

double GlModel::back_faces_hidden_above(int level) const {
  check_representation({ObjectKind::kMesh, level}, *impl_);
  return impl_->back_faces_hidden_above[level];
}

void GlModel::set_cull_hidden_back_faces(bool on) {
  impl_->cull_hidden_back_faces = on;
}

bool GlModel::culls_hidden_back_faces() const {
  return impl_->cull_hidden_back_faces;
}

bool GlModel::culls_back_faces(const Representation& rep, const ObjectInstance& instance,
                               const Camera& camera) const {
  const Impl& m = *impl_;
  if (rep.kind != ObjectKind::kMesh || !m.cull_hidden_back_faces) return false;
  check_representation(rep, m);
  const double above = m.back_faces_hidden_above[std::size_t(rep.level)];
  return std::isfinite(above) && camera.position.z > instance.position.z + instance.scale * above;
}

void GlModel::draw(const Representation& rep, std::span<const ObjectInstance> instances,
                   const Camera& camera) {
  const Group group{rep, instances};
  draw(std::span(&group, 1), camera);
}

void GlModel::draw(std::span<const Group> groups, const Camera& camera) {
  Impl& m = *impl_;
  // Each mesh group's instances the camera is above its hidden-back-face
  // height first: those are drawn with every back face culled.
  std::vector<ObjectInstance> all;
  std::vector<GLsizei> culled(groups.size(), 0);
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const Group& g = groups[i];
    check_representation(g.rep, m);
    const std::size_t begin = all.size();
    all.insert(all.end(), g.instances.begin(), g.instances.end());
    culled[i] = GLsizei(std::stable_partition(all.begin() + begin, all.end(),
                                              [&](const ObjectInstance& o) {
                                                return culls_back_faces(g.rep, o, camera);
                                              }) -
                        (all.begin() + begin));
  }
  if (all.empty()) return;
  // Impostors first built here would capture between draws.
  for (const Group& g : groups) {
    if (g.rep.kind == ObjectKind::kRelief) m.relief_impostor(g.rep.resolution);
    if (g.rep.kind == ObjectKind::kOctahedral) m.octahedral_impostor(g.rep.resolution, g.rep.views);
  }
  m.upload_instances(all);
  GLuint first = 0;
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const Group& g = groups[i];
    const GLsizei count = GLsizei(g.instances.size());
    if (count == 0) continue;
    if (g.rep.kind == ObjectKind::kMesh) {
      m.bind_instances(m.levels[g.rep.level].vao.id());
      const GLuint p = m.mesh_program.id();
      glUseProgram(p);
      const glm::mat4 vp(gl::view_projection_reversed_z(camera));
      glUniformMatrix4fv(glGetUniformLocation(p, "u_vp"), 1, GL_FALSE, glm::value_ptr(vp));
      if (culled[i] > 0) m.draw_level_parts(g.rep.level, p, culled[i], first, true);
      if (count > culled[i])
        m.draw_level_parts(g.rep.level, p, count - culled[i], first + GLuint(culled[i]));
    } else {
      m.bind_instances(m.instance_vao.id());
      if (g.rep.kind == ObjectKind::kRelief)
        m.draw_relief(m.relief_impostor(g.rep.resolution), count, first, camera);
      else
        m.draw_octahedral(m.octahedral_impostor(g.rep.resolution, g.rep.views), count, first,
                          camera);
    }
    first += GLuint(count);
  }
}

}  // namespace terrasprite
