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
#include "terrasprite/common/input_file.h"

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

// Bounds of the vertices the triangles use (glTF files may carry unused ones),
// in double: finite float coordinates can still span more than a float holds.
void place_in_metres(Model& m, const std::string& path, const ModelOptions& options) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (std::uint32_t i : m.indices) {
    lo = glm::min(lo, glm::dvec3(m.positions[i]));
    hi = glm::max(hi, glm::dvec3(m.positions[i]));
  }
  const double height = hi.z - lo.z;
  if (!(height > 0))
    throw InputError(fmt::format("{}: the model has zero height along its up axis", path));
  m.scale_to_m = options.height_m > 0 ? options.height_m / height : 1.0;
  const glm::dvec3 extent = (hi - lo) * m.scale_to_m;
  const double largest = std::max({extent.x, extent.y, extent.z});
  if (!(largest <= kMaxModelExtentM))
    throw InputError(fmt::format(
        "{}: the model spans {:g} m (scale {:g} m per file unit); at most {:g} m is accepted", path,
        largest, m.scale_to_m, kMaxModelExtentM));
  const glm::dvec3 origin(0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), lo.z);
  for (glm::vec3& p : m.positions) p = glm::vec3((glm::dvec3(p) - origin) * m.scale_to_m);
  m.bounds_min = glm::vec3((lo - origin) * m.scale_to_m);
  m.bounds_max = glm::vec3((hi - origin) * m.scale_to_m);
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

std::string one_line(std::string_view text, std::size_t max) {
  constexpr std::size_t kMaxWord = 48;  // a data URI or a path quoted whole
  std::string out;
  std::size_t word = 0;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      if (!out.empty() && out.back() != ' ') out += "; ";
      word = 0;
      continue;
    }
    word = c == ' ' ? 0 : word + 1;
    if (word > kMaxWord) {
      if (word == kMaxWord + 1) out += "...";
      continue;
    }
    out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    if (out.size() > max) return out.substr(0, max) + "...";
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';' || out.back() == '.'))
    out.pop_back();
  return out;
}

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

  place_in_metres(m, path, options);
  return m;
}

}  // namespace objects

UpAxis parse_up_axis(const std::string& text, const char* option) {
  if (text == "y" || text == "Y") return UpAxis::kY;
  if (text == "z" || text == "Z") return UpAxis::kZ;
  throw InputError(fmt::format("{}: '{}' is not an up axis (y or z)", option, text));
}

void check_model_options(const ModelOptions& options, const std::string& path) {
  if (!(options.height_m >= 0 && options.height_m <= kMaxModelHeightM))
    throw InputError(fmt::format("{}: height {:g} m is not in 0..{:g}", path, options.height_m,
                                 kMaxModelHeightM));
}

Model load_model(const std::string& path, const ModelOptions& options) {
  check_model_options(options, path);
  const std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb")
    throw InputError(
        fmt::format("{}: unsupported model format '{}' (use .obj, .gltf or .glb)", path, ext));
  const std::string bytes = read_input_text(path, "model file");
  if (ext == ".obj") return objects::load_obj(path, bytes, options);
  return objects::load_gltf(path, bytes, options);
}

}  // namespace terrasprite
