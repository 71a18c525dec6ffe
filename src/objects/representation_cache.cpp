// SPDX-License-Identifier: MIT
#include "terrasprite/objects/representation_cache.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include "terrasprite/common/cache_dir.h"
#include "terrasprite/common/cache_entry.h"
#include "terrasprite/common/elapsed.h"
#include "terrasprite/output/atomic_file.h"

namespace terrasprite {
namespace {

// Bump when anything a cached entry holds changes meaning: the chain's
// layout, a capture shader, an impostor's texture formats.
constexpr std::uint32_t kFormatVersion = 2;

// Little helpers for the chain's flat layout: a count, then the raw array.
template <class T>
void put(std::string& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  out.append(reinterpret_cast<const char*>(&n), 8);
  out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}
template <class T>
void put(std::string& out, const T& x) {
  out.append(reinterpret_cast<const char*>(&x), sizeof(T));
}

struct Reader {
  std::string_view in;
  bool ok = true;
  template <class T>
  T get() {
    T x{};
    if (in.size() < sizeof(T)) {
      ok = false;
      return x;
    }
    std::memcpy(&x, in.data(), sizeof(T));
    in.remove_prefix(sizeof(T));
    return x;
  }
  template <class T>
  std::vector<T> array() {
    const auto n = get<std::uint64_t>();
    if (!ok || n > in.size() / sizeof(T)) {
      ok = false;
      return {};
    }
    std::vector<T> v(n);
    if (n > 0)
      std::memcpy(v.data(), in.data(), n * sizeof(T));  // an empty vector's data() may be null
    in.remove_prefix(n * sizeof(T));
    return v;
  }
};

}  // namespace

std::string default_cache_dir() {
  return (std::filesystem::path(cache_root()) / "objects").string();
}

std::uint64_t model_content_hash(const Model& m) {
  const auto bytes = [](const auto& v) {
    return std::string_view(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(*v.data()));
  };
  std::uint64_t h = fnv1a(bytes(m.positions));
  h = fnv1a(bytes(m.normals), h);
  h = fnv1a(bytes(m.uvs), h);
  h = fnv1a(bytes(m.indices), h);
  std::string fields = fmt::format("v{}|i{};", m.positions.size(), m.indices.size());
  for (const MeshPart& p : m.parts)
    fields += fmt::format("p{},{},{};", p.first_index, p.index_count, p.material);
  for (const Material& mat : m.materials)
    fields += fmt::format("m{}|{},{},{},{}|{}|{};", mat.name, mat.base_color.r, mat.base_color.g,
                          mat.base_color.b, mat.base_color.a, mat.texture, mat.double_sided);
  for (const Image& t : m.textures) {
    fields += fmt::format("t{}x{};", t.width, t.height);
    h = fnv1a(bytes(t.rgba), h);
  }
  fields +=
      fmt::format("n{}|s{}|b{},{},{},{},{},{}", m.normals_from_file, m.scale_to_m, m.bounds_min.x,
                  m.bounds_min.y, m.bounds_min.z, m.bounds_max.x, m.bounds_max.y, m.bounds_max.z);
  return fnv1a(fields, h);
}

std::string model_source_key(const Model& model, const ModelOptions& m) {
  // The options are folded into the model's content already (axes, size,
  // texture, colour, faces); they are keyed too, so a loader that ignored
  // one still gets entries of its own. faces3: a double-sided material's
  // opposite twins drawn single-sided.
  const std::string params =
      fmt::format("up{}|h{}|c{},{},{},{}|faces3|ds{}", int(m.up), m.height_m, m.color.r, m.color.g,
                  m.color.b, m.color.a, m.double_sided ? int(*m.double_sided) : -1);
  return fmt::format("{:016x}{:016x}", model_content_hash(model), fnv1a(params));
}

RepresentationCache::RepresentationCache(std::filesystem::path dir, std::string key,
                                         std::string stem)
    : dir_(std::move(dir)), key_(std::move(key)), stem_(std::move(stem)) {}

std::filesystem::path RepresentationCache::file(const std::string& what) const {
  return dir_ / fmt::format("{}-{}-{}.rep", stem_, key_, what);
}

std::string RepresentationCache::entry_key(const std::string& what) const {
  return fmt::format("terrasprite representation {} of {} {}", kFormatVersion, key_, what);
}

std::optional<std::string> RepresentationCache::read(
    const std::string& what, std::uint64_t max_size,
    const std::function<const char*(std::string_view)>& check) const {
  if (!enabled()) return std::nullopt;
  const auto t0 = std::chrono::steady_clock::now();
  const std::filesystem::path f = file(what);
  CacheEntryRead r = read_cache_entry(f, entry_key(what), max_size);
  if (!r.payload && r.problem.empty()) return std::nullopt;  // not built yet
  if (r.payload && check)
    if (const char* problem = check(*r.payload)) r = {std::nullopt, problem};
  if (!r.payload) {
    fmt::print(stderr, "warning: ignoring the cache entry {}: {}; building it again\n", f.string(),
               r.problem);
    ++stats_->rejected;
    return std::nullopt;
  }
  ++stats_->hits;
  stats_->read_ms += ms_since(t0);
  return std::move(r.payload);
}

void RepresentationCache::write(const std::string& what, std::string_view payload) const {
  if (!enabled()) return;
  const std::string bytes = encode_cache_entry(entry_key(what), payload);
  if (bytes.empty() || !replace_file_atomically(file(what), bytes))
    fmt::print(stderr, "warning: cannot write the cache entry {}\n", file(what).string());
}

std::string serialize_lod_chain(const std::vector<LodLevel>& chain) {
  std::string out;
  put(out, std::uint64_t(chain.size()));
  for (const LodLevel& lv : chain) {
    put(out, lv.positions);
    put(out, lv.normals);
    put(out, lv.uvs);
    put(out, lv.indices);
    put(out, lv.parts);
    put(out, lv.error_m);
    put(out, std::uint8_t(lv.sloppy));
  }
  return out;
}

std::optional<std::vector<LodLevel>> deserialize_lod_chain(std::string_view bytes,
                                                           std::size_t materials) {
  Reader r{bytes};
  const auto levels = r.get<std::uint64_t>();
  if (!r.ok || levels == 0 || levels > 64) return std::nullopt;
  std::vector<LodLevel> chain(levels);
  for (LodLevel& lv : chain) {
    lv.positions = r.array<glm::vec3>();
    lv.normals = r.array<glm::vec3>();
    lv.uvs = r.array<glm::vec2>();
    lv.indices = r.array<std::uint32_t>();
    lv.parts = r.array<MeshPart>();
    lv.error_m = r.get<double>();
    lv.sloppy = r.get<std::uint8_t>() != 0;
    if (!r.ok || lv.normals.size() != lv.positions.size() || lv.uvs.size() != lv.positions.size() ||
        lv.indices.size() % 3 != 0)
      return std::nullopt;
    for (std::uint32_t i : lv.indices)
      if (i >= lv.positions.size()) return std::nullopt;
    for (const MeshPart& p : lv.parts)
      if (std::uint64_t(p.first_index) + p.index_count > lv.indices.size() || p.material < 0 ||
          std::size_t(p.material) >= materials)
        return std::nullopt;
  }
  if (!r.ok || !r.in.empty()) return std::nullopt;
  return chain;
}

std::string lod_chain_key(const LodOptions& o) {
  // kLodAlgorithm: bumped whenever build_lod_chain makes other levels from the
  // same options (2: sloppy steps per colour region; 3: small parts left
  // out, small_components.h), so older chains miss.
  constexpr int kLodAlgorithm = 3;
  return fmt::format("lod-a{}-r{}-f{}-t{}-c{}", kLodAlgorithm, o.ratio, o.min_fraction,
                     o.min_triangles, o.crease_deg);
}

std::uint64_t lod_chain_max_bytes(const Model& model, const LodOptions& o) {
  // build_lod_chain's contract: level 0 is the model; each next level has at
  // most `ratio` times the triangles of the one before, at most three
  // vertices and one part per triangle. Twice that, for rounding.
  constexpr double kMaxLevels = 64, kLevelFields = 5 * 8 + 8 + 1;
  constexpr double kPerTriangle = 3 * sizeof(std::uint32_t) + sizeof(MeshPart) +
                                  3 * (2 * sizeof(glm::vec3) + sizeof(glm::vec2));
  const double t = double(model.triangles()), ratio = std::clamp(o.ratio, 0.0, 1.0);
  const double later = ratio < 1
                           ? std::min(kMaxLevels * t, 2 * t * ratio / (1 - ratio)) + kMaxLevels
                           : kMaxLevels * t;
  const double level0 = double(model.vertices()) * (2 * sizeof(glm::vec3) + sizeof(glm::vec2)) +
                        t * 3 * sizeof(std::uint32_t) +
                        double(model.parts.size()) * sizeof(MeshPart);
  return std::uint64_t(8 + kMaxLevels * kLevelFields + level0 + later * kPerTriangle);
}

std::vector<LodLevel> cached_lod_chain(const Model& model, const LodOptions& o,
                                       const RepresentationCache& cache) {
  const std::string what = lod_chain_key(o);
  std::optional<std::vector<LodLevel>> chain;
  cache.read(what, lod_chain_max_bytes(model, o), [&](std::string_view bytes) -> const char* {
    chain = deserialize_lod_chain(bytes, model.materials.size());
    return chain ? nullptr : "not a LOD chain of this model";
  });
  if (chain) return std::move(*chain);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<LodLevel> built = build_lod_chain(model, o);
  if (cache.enabled()) {
    cache.stats().build_ms += ms_since(t0);
    ++cache.stats().misses;
    cache.write(what, serialize_lod_chain(built));
  }
  return built;
}

}  // namespace terrasprite
