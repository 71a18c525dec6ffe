// SPDX-License-Identifier: MIT
#include "terrasprite/objects/representation_cache.h"

#include <fmt/format.h>
#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>

#include "terrasprite/common/cache_dir.h"
#include "terrasprite/common/elapsed.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace {

// Bump when anything a cached entry holds changes meaning: the chain's
// layout, a capture shader, an impostor's texture formats.
constexpr std::uint32_t kFormatVersion = 1;
constexpr char kMagic[8] = {'T', 'S', 'R', 'E', 'P', 'C', '0', '1'};
constexpr std::size_t kHeader = 8 + 4 + 8;  // magic, version, payload size; then a zstd frame

/// Decompresses the one zstd frame `in`, which claims `size` bytes, into
/// `out`, growing it as data arrives: a damaged size field claiming
/// terabytes allocates no more than the frame yields. False when the frame
/// is corrupt (its checksum included), holds another size or has bytes after it.
bool decompress_frame(std::string_view in, std::uint64_t size, std::string& out) {
  constexpr std::uint64_t kFirstChunk = 1 << 20;
  const std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx*)> d(ZSTD_createDCtx(),
                                                                  ZSTD_freeDCtx);
  ZSTD_inBuffer src{in.data(), in.size(), 0};
  out.clear();
  std::size_t done = 0;
  for (;;) {
    if (done == out.size() && out.size() < size)
      out.resize(std::size_t(std::min<std::uint64_t>(
          size, std::max<std::uint64_t>(kFirstChunk, 2 * std::uint64_t(out.size())))));
    ZSTD_outBuffer dst{out.data(), out.size(), done};
    const std::size_t read_before = src.pos;
    const std::size_t ret = ZSTD_decompressStream(d.get(), &dst, &src);
    if (ZSTD_isError(ret)) return false;
    const bool progress = dst.pos != done || src.pos != read_before;
    done = dst.pos;
    if (ret == 0) return done == size && src.pos == src.size;
    if (!progress) return false;  // input used up, or more output than claimed
  }
}

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
    std::memcpy(v.data(), in.data(), n * sizeof(T));
    in.remove_prefix(n * sizeof(T));
    return v;
  }
};

}  // namespace

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h) {
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::string read_file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(fmt::format("{}: cannot read", path.string()));
  std::string bytes(std::size_t(in.tellg()), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), std::streamsize(bytes.size())))
    throw InputError(fmt::format("{}: cannot read", path.string()));
  return bytes;
}

bool write_file_atomically(const std::filesystem::path& file, std::string_view bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (file.has_parent_path()) fs::create_directories(file.parent_path(), ec);
  // One temporary name per process: two processes filling the same entry
  // (ctest -j, two terminals) each rename a whole file of their own.
  const fs::path tmp = file.string() + fmt::format(".{}.tmp", ::getpid());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), std::streamsize(bytes.size()));
    if (!f) {
      f.close();
      fs::remove(tmp, ec);
      return false;
    }
  }
  fs::rename(tmp, file, ec);
  if (ec) fs::remove(tmp, ec);
  return !ec;
}

std::string default_cache_dir() {
  return (std::filesystem::path(cache_root()) / "objects").string();
}

std::uint64_t model_files_hash(const std::string& model_file, const ModelOptions& m) {
  std::uint64_t h = fnv1a(read_file_bytes(model_file));
  return m.texture.empty() ? h : fnv1a(read_file_bytes(m.texture), h);
}

std::string model_source_key(const std::string& model_file, const ModelOptions& m) {
  const std::uint64_t h = model_files_hash(model_file, m);
  // faces2: single-sided materials drawn without their back faces; faces3:
  // a double-sided material's opposite twins drawn single-sided.
  const std::string params = fmt::format("up{}|h{}|tex{}|c{},{},{},{}|faces3|ds{}", int(m.up),
                                         m.height_m, m.texture, m.color.r, m.color.g, m.color.b,
                                         m.color.a, m.double_sided ? int(*m.double_sided) : -1);
  return fmt::format("{:016x}{:016x}", h, fnv1a(params));
}

RepresentationCache::RepresentationCache(std::filesystem::path dir, std::string key,
                                         std::string stem)
    : dir_(std::move(dir)), key_(std::move(key)), stem_(std::move(stem)) {}

std::filesystem::path RepresentationCache::file(const std::string& what) const {
  return dir_ / fmt::format("{}-{}-{}.rep", stem_, key_, what);
}

std::optional<std::string> RepresentationCache::read(
    const std::string& what, const std::function<const char*(std::string_view)>& check) const {
  if (!enabled()) return std::nullopt;
  const auto t0 = std::chrono::steady_clock::now();
  const std::filesystem::path f = file(what);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(f, ec)) return std::nullopt;
  std::string bytes;
  try {
    bytes = read_file_bytes(f);
  } catch (const InputError&) {
    bytes.clear();
  }
  Reader r{bytes};
  char magic[8] = {};
  if (bytes.size() >= 8) std::memcpy(magic, bytes.data(), 8);
  r.in.remove_prefix(std::min<std::size_t>(8, bytes.size()));
  const auto version = r.get<std::uint32_t>();
  const auto size = r.get<std::uint64_t>();
  std::string payload;
  const char* problem = nullptr;
  if (bytes.size() < kHeader || std::memcmp(magic, kMagic, 8) != 0) {
    problem = "not a terrasprite cache entry";
  } else if (version != kFormatVersion) {
    problem = "another format version";
  } else if (size >= ZSTD_CONTENTSIZE_ERROR) {
    problem = "no payload size";
  } else if (ZSTD_getFrameContentSize(r.in.data(), r.in.size()) != size ||
             ZSTD_findFrameCompressedSize(r.in.data(), r.in.size()) != r.in.size()) {
    problem = "truncated";
  } else if (!decompress_frame(r.in, size, payload)) {
    // The frame carries a checksum of its content: corruption fails here.
    problem = "checksum mismatch or corrupt data";
  } else if (check) {
    problem = check(payload);
  }
  if (problem) {
    fmt::print(stderr, "warning: ignoring the cache entry {}: {}; building it again\n", f.string(),
               problem);
    ++stats_->rejected;
    return std::nullopt;
  }
  ++stats_->hits;
  stats_->read_ms += ms_since(t0);
  return payload;
}

void RepresentationCache::write(const std::string& what, std::string_view payload) const {
  if (!enabled()) return;
  std::string bytes(kMagic, 8);
  put(bytes, kFormatVersion);
  put(bytes, std::uint64_t(payload.size()));
  // zstd level 1 with a content checksum: an octahedral atlas is mostly
  // empty texels (the bunny's 512 x 12 views: 302 MB -> ~40 MB), and fast
  // to read back; the checksum catches a damaged file.
  const std::size_t header = bytes.size();
  bytes.resize(header + ZSTD_compressBound(payload.size()));
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, 1);
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_checksumFlag, 1);
  const std::size_t n = ZSTD_compress2(cctx, bytes.data() + header, bytes.size() - header,
                                       payload.data(), payload.size());
  ZSTD_freeCCtx(cctx);
  if (ZSTD_isError(n) || !(bytes.resize(header + n), write_file_atomically(file(what), bytes)))
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

std::vector<LodLevel> cached_lod_chain(const Model& model, const LodOptions& o,
                                       const RepresentationCache& cache) {
  const std::string what = lod_chain_key(o);
  std::optional<std::vector<LodLevel>> chain;
  cache.read(what, [&](std::string_view bytes) -> const char* {
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
