// SPDX-License-Identifier: MIT
// glTF 2.0 (.gltf, .glb) through tinygltf: the default scene's node tree with
// its transforms, every triangle primitive's POSITION, NORMAL and TEXCOORD_0,
// base-colour factors and textures. Every accessor is bounds-checked against
// its buffer before a byte is read.
#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <iterator>
#include <limits>
#include <map>
#include <string_view>

#include "objects/model_builder.h"
#include "terrasprite/common/error.h"

namespace terrasprite::objects {
namespace {

constexpr int kMaxNodeDepth = 64;
// Node visits along every path of the scene: a graph whose children repeat
// at each level has 2^depth paths.
constexpr std::size_t kMaxNodeVisits = 100000;
// A buffer or image file's size, read whole.
constexpr std::uintmax_t kMaxReferencedBytes = std::uintmax_t(2) << 30;
// Nesting of JSON arrays and objects: tinygltf parses recursively.
constexpr int kMaxJsonDepth = 128;

struct Reader {
  const tinygltf::Model& g;
  const std::string& path;
  const std::string& warnings;  ///< tinygltf's, for a texture it could not read

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: {}", path, what));
  }

  // Pointer to element i of accessor a, having checked that every element fits.
  struct View {
    const unsigned char* base = nullptr;
    std::size_t stride = 0, count = 0;
    int component = 0, width = 0;  // component type, components per element
    bool normalized = false;
  };
  View view(int accessor, int want_width) const {
    if (accessor < 0 || accessor >= int(g.accessors.size()))
      fail("an accessor index is out of range");
    const tinygltf::Accessor& a = g.accessors[accessor];
    if (a.sparse.isSparse) fail("sparse accessors are not supported");
    if (a.bufferView < 0 || a.bufferView >= int(g.bufferViews.size()))
      fail("an accessor has no valid buffer view");
    const tinygltf::BufferView& bv = g.bufferViews[a.bufferView];
    if (bv.buffer < 0 || bv.buffer >= int(g.buffers.size()))
      fail("a buffer view has no valid buffer");
    const auto& buf = g.buffers[bv.buffer].data;
    const int width = tinygltf::GetNumComponentsInType(a.type);
    const int csize = tinygltf::GetComponentSizeInBytes(a.componentType);
    if (width != want_width || csize <= 0) fail("an accessor has an unsupported type");
    View v{nullptr, bv.byteStride ? bv.byteStride : std::size_t(width * csize),
           a.count, a.componentType,
           width,   a.normalized};
    const std::size_t elem = std::size_t(width) * csize;
    const std::size_t start = bv.byteOffset + a.byteOffset;
    if (a.count == 0) return v;
    const std::size_t need = a.byteOffset + (a.count - 1) * v.stride + elem;
    if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset ||
        need > bv.byteLength || a.count > buf.size())
      fail("an accessor reaches past the end of its buffer (truncated file?)");
    v.base = buf.data() + start;
    return v;
  }
  static double component(const View& v, std::size_t i, int k) {
    const unsigned char* p = v.base + i * v.stride;
    switch (v.component) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p + 4 * k, 4);
        return f;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return v.normalized ? p[k] / 255.0 : p[k];
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t s;
        std::memcpy(&s, p + 2 * k, 2);
        return v.normalized ? s / 65535.0 : s;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t u;
        std::memcpy(&u, p + 4 * k, 4);
        return u;
      }
      default:
        return 0.0;
    }
  }
};

glm::dmat4 node_matrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
  glm::dmat4 t(1.0), r(1.0), s(1.0);
  if (n.translation.size() == 3)
    t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1);
  if (n.rotation.size() == 4)
    r = glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3)
    s = glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return t * r * s;
}

void add_materials(RawModel& raw, const tinygltf::Model& g, const Reader& rd) {
  std::map<int, int> texture_of_image;
  for (const tinygltf::Material& m : g.materials) {
    Material out{m.name, glm::vec4(1.f), -1, m.doubleSided};
    const auto& f = m.pbrMetallicRoughness.baseColorFactor;
    if (f.size() == 4) out.base_color = glm::vec4(f[0], f[1], f[2], f[3]);
    const int ti = m.pbrMetallicRoughness.baseColorTexture.index;
    if (ti >= 0) {
      if (ti >= int(g.textures.size()) || g.textures[ti].source < 0 ||
          g.textures[ti].source >= int(g.images.size()))
        rd.fail(fmt::format("material '{}' names a texture that does not exist", m.name));
      const int src = g.textures[ti].source;
      auto [it, fresh] = texture_of_image.try_emplace(src, int(raw.textures.size()));
      if (fresh) {
        const tinygltf::Image& im = g.images[src];
        if (im.width <= 0 || im.height <= 0 || im.bits != 8 || im.component < 1 ||
            im.component > 4 || im.image.size() != std::size_t(im.width) * im.height * im.component)
          rd.fail(fmt::format("texture '{}' is missing or unreadable{}",
                              one_line(im.uri.empty() ? im.name : im.uri, 60),
                              rd.warnings.empty() ? "" : " (" + one_line(rd.warnings, 120) + ")"));
        Image img(im.width, im.height);
        for (std::size_t p = 0; p < std::size_t(im.width) * im.height; ++p)
          for (int c = 0; c < 4; ++c) {
            const int from = im.component >= 3 ? c : (c < 3 ? 0 : 1);
            img.rgba[p * 4 + c] = c == 3 && (im.component == 3 || im.component == 1)
                                      ? 255
                                      : im.image[p * im.component + from];
          }
        raw.textures.push_back(std::move(img));
        raw.texture_names.push_back(im.uri.empty() ? im.name : im.uri);
      }
      out.texture = it->second;
    }
    raw.materials.push_back(out);
  }
  // glTF's default material is single-sided.
  raw.materials.push_back({"default", glm::vec4(0.8f, 0.8f, 0.8f, 1.f), -1, false});
  raw.orientation_from_file = true;
}

bool add_primitive(RawModel& raw, const Reader& rd, const tinygltf::Primitive& prim,
                   const glm::dmat4& xf) {
  if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
    return true;  // points, lines: no surface
  auto pos_it = prim.attributes.find("POSITION");
  if (pos_it == prim.attributes.end()) rd.fail("a primitive has no POSITION");
  const Reader::View pos = rd.view(pos_it->second, 3);
  if (pos.component != TINYGLTF_COMPONENT_TYPE_FLOAT) rd.fail("POSITION is not float");
  Reader::View nrm, uv;
  if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end())
    nrm = rd.view(it->second, 3);
  if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end())
    uv = rd.view(it->second, 2);
  if ((nrm.base && nrm.count != pos.count) || (uv.base && uv.count != pos.count))
    rd.fail("a primitive's attributes have different counts");
  if (pos.count > kMaxModelVertices - raw.positions.size())
    rd.fail(fmt::format("the scene instances more than {} vertices", kMaxModelVertices));
  const std::uint32_t first = std::uint32_t(raw.positions.size());
  const glm::dmat3 nxf = glm::inverseTranspose(glm::dmat3(xf));
  for (std::size_t i = 0; i < pos.count; ++i) {
    glm::dvec3 p(Reader::component(pos, i, 0), Reader::component(pos, i, 1),
                 Reader::component(pos, i, 2));
    raw.positions.push_back(glm::vec3(xf * glm::dvec4(p, 1.0)));
    glm::dvec3 n(0.0);
    if (nrm.base)
      n = nxf * glm::dvec3(Reader::component(nrm, i, 0), Reader::component(nrm, i, 1),
                           Reader::component(nrm, i, 2));
    raw.normals.push_back(glm::vec3(n));
    raw.uvs.push_back(uv.base ? glm::vec2(Reader::component(uv, i, 0), Reader::component(uv, i, 1))
                              : glm::vec2(0.f));
  }
  std::vector<std::uint32_t> idx;
  if (prim.indices >= 0) {
    const Reader::View iv = rd.view(prim.indices, 1);
    if (iv.count > 3 * kMaxModelTriangles - raw.indices.size())
      rd.fail(fmt::format("the scene instances more than {} triangles", kMaxModelTriangles));
    for (std::size_t i = 0; i < iv.count; ++i) {
      const double k = Reader::component(iv, i, 0);
      if (k >= double(pos.count))
        rd.fail(fmt::format("index {} is out of range ({} vertices)", k, pos.count));
      idx.push_back(first + std::uint32_t(k));
    }
  } else {
    for (std::size_t i = 0; i < pos.count; ++i) idx.push_back(first + std::uint32_t(i));
  }
  if (glm::determinant(glm::dmat3(xf)) < 0)  // a mirroring transform flips the winding
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) std::swap(idx[t + 1], idx[t + 2]);
  const int material = prim.material >= 0 && prim.material < int(raw.materials.size()) - 1
                           ? prim.material
                           : int(raw.materials.size()) - 1;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    raw.indices.insert(raw.indices.end(), idx.begin() + t, idx.begin() + t + 3);
    raw.triangle_material.push_back(material);
  }
  return nrm.base != nullptr;
}

void add_node(RawModel& raw, const Reader& rd, int node, const glm::dmat4& parent, int depth,
              std::size_t& visits, bool& all_normals) {
  if (node < 0 || node >= int(rd.g.nodes.size())) rd.fail("a node index is out of range");
  if (depth > kMaxNodeDepth) rd.fail("the node tree is too deep (a cycle?)");
  if (++visits > kMaxNodeVisits)
    rd.fail(
        fmt::format("the scene reaches nodes over {} times (shared children?)", kMaxNodeVisits));
  const tinygltf::Node& n = rd.g.nodes[node];
  const glm::dmat4 xf = parent * node_matrix(n);
  if (n.mesh >= int(rd.g.meshes.size())) rd.fail("a node names a mesh that does not exist");
  if (n.mesh >= 0)
    for (const tinygltf::Primitive& p : rd.g.meshes[n.mesh].primitives)
      all_normals = add_primitive(raw, rd, p, xf) && all_normals;  // one without: compute all
  for (int c : n.children) add_node(raw, rd, c, xf, depth + 1, visits, all_normals);
}

// The JSON text of a .gltf, or the JSON chunk of a .glb (whatever is there
// when the header is cut short: tinygltf reports that).
std::string_view json_text(const std::string& bytes, bool binary) {
  if (!binary) return bytes;
  if (bytes.size() < 20) return {};
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return std::string_view(bytes).substr(20, length);
}

void check_json_depth(std::string_view json, const std::string& path) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw InputError(
            fmt::format("{}: the JSON nests deeper than {} levels", path, kMaxJsonDepth));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

// Files a glTF refers to (buffers, images): only regular files, each
// problem named, no path expansion.
bool file_exists(const std::string& file, void*) {
  std::error_code ec;
  return std::filesystem::exists(file, ec);
}

std::string file_as_named(const std::string& file, void*) {
  return file;
}

bool read_referenced_file(std::vector<unsigned char>* out, std::string* err,
                          const std::string& file, void*) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  const char* problem = !fs::exists(st)                                 ? "no such file"
                        : fs::is_directory(st)                          ? "is a directory"
                        : !fs::is_regular_file(st)                      ? "is not a regular file"
                        : fs::file_size(file, ec) > kMaxReferencedBytes ? "is larger than 2 GiB"
                                                                        : nullptr;
  if (!problem) {
    std::ifstream in(file, std::ios::binary);
    out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) problem = "cannot be read";
  }
  if (problem && err) *err += problem;
  return problem == nullptr;
}

bool write_nothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the model loader writes no files";
  return false;
}

}  // namespace

Model load_gltf(const std::string& path, const std::string& bytes, const ModelOptions& options) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  const bool binary = ext == ".glb";
  check_json_depth(json_text(bytes, binary), path);
  if (bytes.size() > std::numeric_limits<unsigned>::max())
    throw InputError(fmt::format("{}: larger than 4 GiB", path));
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({file_exists, file_as_named, read_referenced_file, write_nothing, nullptr});
  tinygltf::Model g;
  std::string err, warn;
  const std::string dir = std::filesystem::path(path).parent_path().string();
  const bool ok =
      binary
          ? loader.LoadBinaryFromMemory(&g, &err, &warn,
                                        reinterpret_cast<const unsigned char*>(bytes.data()),
                                        unsigned(bytes.size()), dir)
          : loader.LoadASCIIFromString(&g, &err, &warn, bytes.data(), unsigned(bytes.size()), dir);
  if (!ok) throw InputError(fmt::format("{}: not a readable glTF file ({})", path, one_line(err)));
  RawModel raw;
  const Reader rd{g, path, warn};
  add_materials(raw, g, rd);
  std::vector<int> roots;
  if (!g.scenes.empty()) {
    const int s = g.defaultScene >= 0 && g.defaultScene < int(g.scenes.size()) ? g.defaultScene : 0;
    roots = g.scenes[s].nodes;
  } else {
    for (int i = 0; i < int(g.nodes.size()); ++i) roots.push_back(i);  // no scene: every node
  }
  std::size_t visits = 0;
  bool all_normals = true;
  for (int r : roots) add_node(raw, rd, r, glm::dmat4(1.0), 0, visits, all_normals);
  if (!all_normals) raw.normals.clear();
  return finish_model(std::move(raw), path, options);
}

}  // namespace terrasprite::objects
