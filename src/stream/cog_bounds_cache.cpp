// SPDX-License-Identifier: MIT
#include "stream/cog_bounds_cache.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "terrasprite/common/cache_dir.h"
#include "terrasprite/common/cache_entry.h"
#include "terrasprite/output/atomic_file.h"

namespace terrasprite {
namespace {

// Bump when the pass's result changes meaning.
constexpr int kBoundsFormat = 2;
constexpr std::streamsize kEdgeBytes = 64 << 10;

std::string file_of(const std::string& dir, const std::string& key) {
  return fmt::format("{}/{:016x}.bounds", dir, fnv1a(key));
}

/// FNV-1a of the first and the last kEdgeBytes of `path` (a COG's header and
/// tile offsets, and its last tiles); 0 when it cannot be read.
std::uint64_t edge_hash(const std::string& path, std::uintmax_t size) {
  std::ifstream f(path, std::ios::binary);
  std::string head(std::size_t(std::min<std::uintmax_t>(size, kEdgeBytes)), '\0'), tail = head;
  if (!f.read(head.data(), std::streamsize(head.size()))) return 0;
  f.seekg(std::streamoff(size - tail.size()));
  if (!f.read(tail.data(), std::streamsize(tail.size()))) return 0;
  return fnv1a(tail, fnv1a(head));
}

/// The pass's payload: lo, hi, then each held level's cells.
std::uint64_t payload_size(int W, int H, int bound_from, int bound_levels) {
  std::uint64_t n = 2;
  for (int L = bound_from; L < bound_levels; ++L)
    n += std::uint64_t(TerrainGrid::bound_cells(W, L)) * TerrainGrid::bound_cells(H, L);
  return n * sizeof(float);
}

/// Whether the bounds can be a pass's result: lo <= hi, both finite; a cell
/// holds samples (its bound is at least lo) or none (-inf, beyond the
/// raster's edge), never NaN; each level's largest bound reaches hi.
bool plausible(const std::vector<std::vector<float>>& levels, float lo, float hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) return false;
  for (const std::vector<float>& v : levels) {
    float top = -INFINITY;
    for (float b : v) {
      if (std::isnan(b) || (b < lo && b != -INFINITY)) return false;
      top = std::max(top, b);
    }
    if (top < hi) return false;
  }
  return true;
}

}  // namespace

std::string bounds_cache_dir(bool& explicit_dir) {
  return (std::filesystem::path(cache_root(&explicit_dir)) / "cog-bounds").string();
}

std::string bounds_cache_key(const CogInput& in, int width, int height, int bound_from,
                             int bound_levels, bool has_nodata, double nodata) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::weakly_canonical(in.path, ec);
  struct stat st {};
  if (::stat(in.path.c_str(), &st) != 0) return {};
  // The file's identity (device, inode) and its change time: any write to it
  // moves st_ctime, which no user can set back, so an unchanged fingerprint
  // is an unchanged file without reading a gigabyte; the hash of its first
  // and last blocks catches a copy restored with its old times.
  std::string k = fmt::format(
      "terrasprite cog bounds {}|{}|dev{}|ino{}|size{}|mtime{}.{:09}|ctime{}.{:09}|edges{:016x}",
      kBoundsFormat, p.string(), st.st_dev, st.st_ino, st.st_size, st.st_mtim.tv_sec,
      st.st_mtim.tv_nsec, st.st_ctim.tv_sec, st.st_ctim.tv_nsec,
      edge_hash(in.path, std::uintmax_t(st.st_size)));
  k += fmt::format("|{}x{}|{}|{}|{}|{}", width, height, bound_from, bound_levels, has_nodata,
                   nodata);
  for (const CogInput::Raster& r : in.height_rasters) k += fmt::format("|{}x{}", r.w, r.h);
  return k;
}

bool load_cog_bounds(const std::string& dir, const std::string& key, int W, int H, int bound_from,
                     int bound_levels, CogInput& in, float& lo, float& hi) {
  if (key.empty()) return false;
  const std::string file = file_of(dir, key);
  const std::uint64_t size = payload_size(W, H, bound_from, bound_levels);
  CacheEntryRead r = read_cache_entry(file, key, size);
  if (r.payload && r.payload->size() != size) r = {std::nullopt, "not the size of these bounds"};
  std::vector<std::vector<float>> levels;
  float range[2] = {0, 0};
  if (r.payload) {
    const char* p = r.payload->data();
    std::memcpy(range, p, sizeof range);
    p += sizeof range;
    for (int L = bound_from; L < bound_levels; ++L) {
      std::vector<float>& v = levels.emplace_back(std::size_t(TerrainGrid::bound_cells(W, L)) *
                                                  TerrainGrid::bound_cells(H, L));
      std::memcpy(v.data(), p, v.size() * sizeof(float));
      p += v.size() * sizeof(float);
    }
    if (!plausible(levels, range[0], range[1])) r = {std::nullopt, "bounds no pass can make"};
  }
  if (!r.payload) {
    if (!r.problem.empty())
      fmt::print(stderr,
                 "terrasprite: note: ignoring the cached bounds {}: {}; computing them again\n",
                 file, r.problem);
    return false;
  }
  in.bound = std::move(levels);
  in.bound_from = bound_from;
  lo = range[0];
  hi = range[1];
  return true;
}

void save_cog_bounds(const std::string& dir, const std::string& key, const CogInput& in, float lo,
                     float hi) {
  if (key.empty()) return;
  std::string payload;
  const float range[2] = {lo, hi};
  payload.append(reinterpret_cast<const char*>(range), sizeof range);
  for (const auto& v : in.bound)
    payload.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float));
  const std::string bytes = encode_cache_entry(key, payload);
  if (bytes.empty() || !replace_file_atomically(file_of(dir, key), bytes))
    fmt::print(stderr, "terrasprite: warning: {}: cannot cache the bounds of {} there\n", dir,
               in.path);
}

}  // namespace terrasprite
