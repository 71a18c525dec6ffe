// SPDX-License-Identifier: MIT
// Wavefront OBJ through tinyobjloader: faces triangulated, one vertex per
// distinct (position, uv, normal) triple, materials from the .mtl (Kd and
// map_Kd), or the caller's texture / colour when the file has none.
#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "objects/model_builder.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/common/error.h"

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

// tinyobjloader reads an unparsable coordinate ("nan", "1e999", "x") as 0;
// a second look at the `v` lines refuses them instead.
void check_vertex_lines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (long n = 1; std::getline(in, line); ++n) {
    if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
    std::istringstream fields(line.substr(2));
    std::string f;
    for (int k = 0; k < 3 && fields >> f; ++k) {
      char* end = nullptr;
      const double v = std::strtod(f.c_str(), &end);
      if (end == f.c_str() || *end != '\0' || !std::isfinite(v))
        throw InputError(
            fmt::format("{}: line {}: vertex coordinate '{}' is not a finite number", path, n, f));
    }
  }
}

}  // namespace

Model load_obj(const std::string& path, const ModelOptions& options) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = std::filesystem::path(path).parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string err = reader.Error();
    while (!err.empty() && (err.back() == '\n' || err.back() == '.')) err.pop_back();
    throw InputError(fmt::format("{}: not a readable OBJ file ({})", path, err));
  }
  if (reader.Warning().find("invalid vertex index") != std::string::npos)
    throw InputError(fmt::format("{}: a face has a vertex index out of range", path));
  check_vertex_lines(path);
  const tinyobj::attrib_t& a = reader.GetAttrib();
  RawModel raw;
  add_materials(raw, reader.GetMaterials(), path, options);
  const int fallback = int(raw.materials.size()) - 1;
  const long nv = long(a.vertices.size() / 3), nt = long(a.texcoords.size() / 2),
             nn = long(a.normals.size() / 3);
  bool all_normals = true;
  std::map<std::tuple<int, int, int>, std::uint32_t> vertex_of;
  for (const tinyobj::shape_t& s : reader.GetShapes()) {
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
