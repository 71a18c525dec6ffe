// SPDX-License-Identifier: MIT
// Wavefront OBJ through tinyobjloader: faces triangulated, one vertex per
// distinct (position, uv, normal) triple, materials from the .mtl (Kd and
// map_Kd), or the caller's texture / colour when the file has none.
#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <streambuf>
#include <string_view>
#include <tuple>

#include "objects/model_builder.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::objects {
namespace {

Image load_texture(const std::string& model, const std::string& file) {
  try {
    return load_image(file);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: texture {}: {}", model, file, e.what()));
  }
}

// The file's materials, then one fallback for faces without a material.
void add_materials(RawModel& raw, const std::vector<tinyobj::material_t>& mats,
                   const std::string& path, const ModelOptions& options) {
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::map<std::string, int> loaded;
  for (const tinyobj::material_t& m : mats) {
    Material out{m.name, glm::vec4(m.diffuse[0], m.diffuse[1], m.diffuse[2], 1.f), -1};
    if (!m.diffuse_texname.empty()) {
      const std::string file = (dir / m.diffuse_texname).string();
      auto [it, fresh] = loaded.try_emplace(file, int(raw.textures.size()));
      if (fresh) {
        raw.textures.push_back(load_texture(path, file));
        raw.texture_names.push_back(m.diffuse_texname);
      }
      out.texture = it->second;
      out.base_color = glm::vec4(1.f);  // Kd is often 0.8 grey beside a map; the map wins
    }
    raw.materials.push_back(out);
  }
  Material fallback{"default", options.color, -1};
  if (!options.texture.empty()) {
    raw.textures.push_back(load_texture(path, options.texture));
    raw.texture_names.push_back(std::filesystem::path(options.texture).filename().string());
    fallback.texture = int(raw.textures.size()) - 1;
    fallback.base_color = glm::vec4(1.f);
  }
  raw.materials.push_back(fallback);
}

// A piece of the file quoted in a message: at most 40 characters, those
// that do not print as '?'.
std::string obj_excerpt(std::string_view text) {
  constexpr std::size_t kMax = 40;
  std::string out;
  for (char c : text.substr(0, kMax)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return text.size() <= kMax ? out : out + "...";
}

// What tinyobjloader separates fields with.
bool is_space(char c) {
  return c == ' ' || c == '\t';
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t from = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > from) out.push_back(line.substr(from, i - from));
  }
  return out;
}

// A decimal number that fits a float: tinyobjloader reads anything else
// ("nan", "1e999", "0x1p3", "x") as 0 or infinity.
bool is_float_number(std::string_view f) {
  if (f.empty() || f.find_first_not_of("0123456789+-.eE") != std::string_view::npos) return false;
  const std::string s(f);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(v) && std::abs(v) <= FLT_MAX;
}

// Counts of each element defined so far, and the largest index faces use.
struct ObjCounts {
  long v = 0, vt = 0, vn = 0;
  long max_v = 0, max_vt = 0, max_vn = 0;
};

// One face corner, "v", "v/t", "v//n" or "v/t/n": each index non-zero, a
// negative one counting back from the elements defined so far.
bool check_corner(std::string_view c, ObjCounts& n) {
  long* const defined[3] = {&n.v, &n.vt, &n.vn};
  long* const largest[3] = {&n.max_v, &n.max_vt, &n.max_vn};
  for (int k = 0; k < 3; ++k) {
    const std::size_t slash = std::min(c.find('/'), c.size());
    const std::string_view part = c.substr(0, slash);
    const bool last = slash == c.size();
    if (!part.empty() || k != 1 || last) {  // only the uv may be left out
      long i = 0;
      const char* b = part.data() + (!part.empty() && part[0] == '-');
      const auto [p, ec] = std::from_chars(b, part.data() + part.size(), i);
      if (part.empty() || ec != std::errc() || p != part.data() + part.size() || i == 0)
        return false;
      if (part[0] == '-' && i > *defined[k]) return false;
      if (part[0] != '-') *largest[k] = std::max(*largest[k], i);
    }
    if (last) return true;
    c.remove_prefix(slash + 1);
  }
  return false;  // a fourth field
}

// Corners of one face: tinyobjloader triangulates a polygon by ear clipping,
// in time quadratic in its corners.
constexpr std::size_t kMaxFaceCorners = 1000;

// Where a statement is, for its message.
struct ObjLine {
  const std::string& path;
  long number;
};
std::string obj_line_text(const ObjLine& l) {
  return fmt::format("{}: line {}", l.path, l.number);
}

// One statement; throws naming the line for what tinyobjloader would read
// as zeros, skip, or spend quadratic time on.
void check_statement(const std::vector<std::string_view>& f, ObjCounts& n, const ObjLine& at) {
  const std::string_view key = f[0];
  if (key == "v" || key == "vt" || key == "vn") {
    const std::size_t need = key == "vt" ? 1 : 3;
    if (f.size() < need + 1)
      throw InputError(fmt::format("{}: '{}' has {} of its {} coordinates (truncated file?)",
                                   obj_line_text(at), key, f.size() - 1, need));
    for (std::size_t k = 1; k < f.size(); ++k)
      if (!is_float_number(f[k]))
        throw InputError(fmt::format("{}: coordinate '{}' is not a finite number",
                                     obj_line_text(at), obj_excerpt(f[k])));
    ++(key == "v" ? n.v : key == "vt" ? n.vt : n.vn);
  } else if (key == "f") {
    if (f.size() < 4)
      throw InputError(fmt::format("{}: a face has {} corners, fewer than 3 (truncated file?)",
                                   obj_line_text(at), f.size() - 1));
    if (f.size() - 1 > kMaxFaceCorners)
      throw InputError(fmt::format("{}: a face has {} corners; at most {} are accepted",
                                   obj_line_text(at), f.size() - 1, kMaxFaceCorners));
    for (std::size_t k = 1; k < f.size(); ++k)
      if (!check_corner(f[k], n))
        throw InputError(fmt::format("{}: face corner '{}' is not a vertex index in range",
                                     obj_line_text(at), obj_excerpt(f[k])));
  }
}

// A first pass over the statements tinyobjloader reads silently wrong:
// coordinates that are not finite numbers, faces that are cut short, point
// past the elements or are too large to triangulate, and a last line
// without its end (a truncated file).
void check_obj_text(std::string_view text, const std::string& path) {
  ObjCounts n;
  ObjLine line{path, 0};
  std::size_t at = 0;
  while (at < text.size()) {  // lines end in \n, \r\n or \r, as tinyobjloader reads them
    const std::size_t eol = std::min(text.find_first_of("\r\n", at), text.size());
    ++line.number;
    const std::vector<std::string_view> fields = split_fields(text.substr(at, eol - at));
    if (!fields.empty() && fields[0][0] != '#') {
      if (eol == text.size())
        throw InputError(
            fmt::format("{}: the last line has no end (truncated file?)", obj_line_text(line)));
      check_statement(fields, n, line);
    }
    at = eol + (text.substr(eol, 2) == "\r\n" ? 2 : 1);
  }
  const auto past = [&](const char* what, long used, long defined) {
    if (used > defined)
      throw InputError(fmt::format("{}: a face refers to {} {} of {} (truncated file?)", path, what,
                                   used, defined));
  };
  past("vertex", n.max_v, n.v);
  past("uv", n.max_vt, n.vt);
  past("normal", n.max_vn, n.vn);
}

// The .mtl files `mtllib` names, beside the model; the names of those
// missing are kept for one warning each.
class MaterialFiles : public tinyobj::MaterialReader {
 public:
  explicit MaterialFiles(const std::string& model)
      : model_(model), dir_(std::filesystem::path(model).parent_path()) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* names, std::string* warn, std::string* err) override {
    const std::filesystem::path file = dir_ / name;
    std::error_code ec;
    std::ifstream in;
    if (std::filesystem::is_regular_file(file, ec)) {
      if (std::filesystem::file_size(file, ec) > (std::uintmax_t(1) << 30))
        throw InputError(
            fmt::format("{}: material library {} is larger than 1 GiB", model_, obj_excerpt(name)));
      in.open(file, std::ios::binary);
    }
    if (!in.is_open()) {
      if (std::find(missing.begin(), missing.end(), name) == missing.end()) missing.push_back(name);
      return false;
    }
    tinyobj::LoadMtl(names, materials, &in, warn, err);
    return true;
  }
  std::vector<std::string> missing;

 private:
  const std::string& model_;
  std::filesystem::path dir_;
};

// Reads `bytes` in place, without a copy.
struct BytesBuf : std::streambuf {
  explicit BytesBuf(const std::string& bytes) {
    char* p = const_cast<char*>(bytes.data());
    setg(p, p, p + bytes.size());
  }
};

}  // namespace

Model load_obj(const std::string& path, const std::string& bytes, const ModelOptions& options) {
  check_obj_text(bytes, path);
  tinyobj::attrib_t a;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  BytesBuf buf(bytes);
  std::istream in(&buf);
  MaterialFiles mtl(path);
  if (!tinyobj::LoadObj(&a, &shapes, &materials, &warn, &err, &in, &mtl, true, false))
    throw InputError(fmt::format("{}: not a readable OBJ file ({})", path, one_line(err)));
  if (warn.find("invalid vertex index") != std::string::npos)
    throw InputError(fmt::format("{}: a face has a vertex index out of range", path));
  for (const std::string& m : mtl.missing)
    fmt::print(stderr,
               "warning: {}: material library {} not found; its materials are drawn in "
               "the default colour\n",
               path, obj_excerpt(m));
  RawModel raw;
  add_materials(raw, materials, path, options);
  const int fallback = int(raw.materials.size()) - 1;
  const long nv = long(a.vertices.size() / 3), nt = long(a.texcoords.size() / 2),
             nn = long(a.normals.size() / 3);
  bool all_normals = true;
  std::map<std::tuple<int, int, int>, std::uint32_t> vertex_of;
  for (const tinyobj::shape_t& s : shapes) {
    const auto& idx = s.mesh.indices;
    for (std::size_t c = 0; c < idx.size(); ++c) {
      const tinyobj::index_t i = idx[c];
      if (i.vertex_index < 0 || i.vertex_index >= nv || i.texcoord_index >= nt ||
          i.normal_index >= nn)
        throw InputError(fmt::format("{}: a face has an index out of range", path));
      auto [it, fresh] = vertex_of.try_emplace({i.vertex_index, i.texcoord_index, i.normal_index},
                                               std::uint32_t(raw.positions.size()));
      if (fresh) {
        const float* p = &a.vertices[3 * i.vertex_index];
        raw.positions.emplace_back(p[0], p[1], p[2]);
        raw.uvs.push_back(i.texcoord_index >= 0 ? glm::vec2(a.texcoords[2 * i.texcoord_index],
                                                            a.texcoords[2 * i.texcoord_index + 1])
                                                : glm::vec2(0.f));
        all_normals = all_normals && i.normal_index >= 0;
        raw.normals.push_back(i.normal_index >= 0 ? glm::vec3(a.normals[3 * i.normal_index],
                                                              a.normals[3 * i.normal_index + 1],
                                                              a.normals[3 * i.normal_index + 2])
                                                  : glm::vec3(0.f));
      }
      raw.indices.push_back(it->second);
    }
    for (int m : s.mesh.material_ids)
      raw.triangle_material.push_back(m >= 0 && m < fallback ? m : fallback);
  }
  if (!all_normals) raw.normals.clear();
  // OBJ texture rows start at the bottom; our images start at the top.
  for (glm::vec2& uv : raw.uvs) uv.y = 1.f - uv.y;
  return finish_model(std::move(raw), path, options);
}

}  // namespace terrasprite::objects
