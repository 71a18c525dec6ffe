// SPDX-License-Identifier: MIT
// Loader dispatch and the shared last step of every loader: validation,
// normals, material grouping, up axis, metres.
#include "terrasprite/objects/model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <unordered_map>

#include "objects/model_builder.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

struct PositionKey {
  float x, y, z;
  bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint32_t a, b, c;
    std::memcpy(&a, &k.x, 4);
    std::memcpy(&b, &k.y, 4);
    std::memcpy(&c, &k.z, 4);
    return (a * 73856093u) ^ (b * 19349663u) ^ (c * 83492791u);
  }
};

void validate(const objects::RawModel& raw, const std::string& path) {
  const std::size_t n = raw.positions.size();
  if (raw.indices.size() < 3) throw InputError(fmt::format("{}: the model has no triangles", path));
  for (const glm::vec3& p : raw.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(fmt::format("{}: a vertex position is not finite (NaN or infinity)", path));
  for (std::uint32_t i : raw.indices)
    if (i >= n)
      throw InputError(
          fmt::format("{}: vertex index {} is out of range ({} vertices)", path, i + 1, n));
  for (const Material& m : raw.materials)
    if (m.texture >= int(raw.textures.size()))
      throw InputError(fmt::format("{}: material '{}' names a missing texture", path, m.name));
}

// Bring positions and normals from the file's axes to z up.
void to_z_up(objects::RawModel& raw, UpAxis up) {
  if (up == UpAxis::kZ) return;
  auto rot = [](glm::vec3 v) { return glm::vec3(v.x, -v.z, v.y); };
  for (glm::vec3& p : raw.positions) p = rot(p);
  for (glm::vec3& q : raw.normals) q = rot(q);
}

// Triangles sorted by material (stable), one part per material used.
void group_parts(const objects::RawModel& raw, Model& m) {
  const std::size_t tris = raw.indices.size() / 3;
  std::vector<std::uint32_t> order(tris);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return raw.triangle_material[a] < raw.triangle_material[b];
  });
  m.indices.resize(tris * 3);
  for (std::size_t t = 0; t < tris; ++t) {
    const std::uint32_t s = order[t];
    for (int k = 0; k < 3; ++k) m.indices[t * 3 + k] = raw.indices[s * 3 + k];
    const int mat = raw.triangle_material[s];
    if (m.parts.empty() || m.parts.back().material != mat)
      m.parts.push_back({std::uint32_t(t * 3), 0, mat});
    m.parts.back().index_count += 3;
  }
}

}  // namespace

std::vector<glm::vec3> smooth_normals(const std::vector<glm::vec3>& positions,
                                      const std::vector<std::uint32_t>& indices) {
  // Vertices sharing a position share one accumulator.
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> first;
  std::vector<std::uint32_t> rep(positions.size());
  for (std::uint32_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    rep[i] = first.try_emplace(PositionKey{p.x, p.y, p.z}, i).first->second;
  }
  std::vector<glm::dvec3> acc(positions.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::dvec3 a(positions[indices[t]]), b(positions[indices[t + 1]]),
        c(positions[indices[t + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);  // length = twice the area
    for (int k = 0; k < 3; ++k) acc[rep[indices[t + k]]] += n;
  }
  std::vector<glm::vec3> out(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::dvec3 n = acc[rep[i]];
    const double len = glm::length(n);
    out[i] = len > 0 ? glm::vec3(n / len) : glm::vec3(0, 0, 1);
  }
  return out;
}

namespace objects {

Model finish_model(RawModel raw, const std::string& path, const ModelOptions& options) {
  validate(raw, path);
  to_z_up(raw, options.up);
  Model m;
  m.name = path;
  m.normals_from_file = raw.normals.size() == raw.positions.size();
  // OBJ cannot say which faces are meant to be seen; glTF does, per material.
  const bool single = options.double_sided        ? !*options.double_sided
                      : raw.orientation_from_file ? false
                                                  : closed_and_outward(raw.positions, raw.indices);
  if (options.double_sided || single)
    for (Material& mat : raw.materials) mat.double_sided = !single;
  draw_opposite_twins_single_sided(raw);
  group_parts(raw, m);
  m.positions = std::move(raw.positions);
  if (m.normals_from_file) {
    m.normals = std::move(raw.normals);
    for (glm::vec3& n : m.normals) {
      const float len = glm::length(n);
      n = len > 0 && std::isfinite(len) ? n / len : glm::vec3(0, 0, 1);
    }
  } else {
    m.normals = smooth_normals(m.positions, m.indices);
  }
  m.uvs = raw.uvs.size() == m.positions.size() ? std::move(raw.uvs)
                                               : std::vector<glm::vec2>(m.positions.size());
  m.materials = std::move(raw.materials);
  m.textures = std::move(raw.textures);
  m.texture_names = std::move(raw.texture_names);

  // Bounds of the vertices the triangles use (glTF files may carry unused ones).
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (std::uint32_t i : m.indices) {
    lo = glm::min(lo, m.positions[i]);
    hi = glm::max(hi, m.positions[i]);
  }
  const double height = double(hi.z) - lo.z;
  if (!(height > 0))
    throw InputError(fmt::format("{}: the model has zero height along its up axis", path));
  m.scale_to_m = options.height_m > 0 ? options.height_m / height : 1.0;
  const glm::vec3 origin(0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y), lo.z);
  for (glm::vec3& p : m.positions) p = glm::vec3(glm::dvec3(p - origin) * m.scale_to_m);
  m.bounds_min = glm::vec3(glm::dvec3(lo - origin) * m.scale_to_m);
  m.bounds_max = glm::vec3(glm::dvec3(hi - origin) * m.scale_to_m);
  return m;
}

}  // namespace objects

UpAxis parse_up_axis(const std::string& text, const char* option) {
  if (text == "y" || text == "Y") return UpAxis::kY;
  if (text == "z" || text == "Z") return UpAxis::kZ;
  throw InputError(fmt::format("{}: '{}' is not an up axis (y or z)", option, text));
}

Model load_model(const std::string& path, const ModelOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(fmt::format("{}: no such model file", path));
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return objects::load_obj(path, options);
  if (ext == ".gltf" || ext == ".glb") return objects::load_gltf(path, options);
  throw InputError(
      fmt::format("{}: unsupported model format '{}' (use .obj, .gltf or .glb)", path, ext));
}

}  // namespace terrasprite
