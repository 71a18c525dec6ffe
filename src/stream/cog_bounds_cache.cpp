// SPDX-License-Identifier: MIT
#include "stream/cog_bounds_cache.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "terrasprite/common/cache_dir.h"

namespace terrasprite {
namespace {

constexpr const char* kMagic = "terrasprite-cog-bounds 1";

std::string file_of(const std::string& dir, const std::string& key) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (unsigned char c : key) h = (h ^ c) * 1099511628211ull;
  return fmt::format("{}/{:016x}.bounds", dir, h);
}

}  // namespace

std::string bounds_cache_dir(bool& explicit_dir) {
  return (std::filesystem::path(cache_root(&explicit_dir)) / "cog-bounds").string();
}

std::string bounds_cache_key(const CogInput& in, int width, int height, int bound_from,
                             int bound_levels, bool has_nodata, double nodata) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::weakly_canonical(in.path, ec);
  const auto size = std::filesystem::file_size(in.path, ec);
  const auto mtime = std::filesystem::last_write_time(in.path, ec).time_since_epoch().count();
  std::string k = fmt::format("{}|{}|{}|{}x{}|{}|{}|{}|{}", p.string(), size, mtime, width, height,
                              bound_from, bound_levels, has_nodata, nodata);
  for (const CogInput::Raster& r : in.height_rasters) k += fmt::format("|{}x{}", r.w, r.h);
  return k;
}

bool load_cog_bounds(const std::string& dir, const std::string& key, int W, int H, int bound_from,
                     int bound_levels, CogInput& in, float& lo, float& hi) {
  std::ifstream f(file_of(dir, key), std::ios::binary);
  if (!f) return false;
  std::string magic, k;
  if (!std::getline(f, magic) || magic != kMagic || !std::getline(f, k) || k != key) return false;
  float range[2];
  if (!f.read(reinterpret_cast<char*>(range), sizeof range)) return false;
  std::vector<std::vector<float>> levels;
  for (int L = bound_from; L < bound_levels; ++L) {
    std::vector<float>& v = levels.emplace_back(std::size_t(TerrainGrid::bound_cells(W, L)) * TerrainGrid::bound_cells(H, L));
    if (!f.read(reinterpret_cast<char*>(v.data()), std::streamsize(v.size() * sizeof(float))))
      return false;
  }
  if (f.peek() != std::char_traits<char>::eof()) return false;  // longer than it should be
  in.bound = std::move(levels);
  in.bound_from = bound_from;
  lo = range[0];
  hi = range[1];
  return true;
}

void save_cog_bounds(const std::string& dir, const std::string& key, const CogInput& in, float lo,
                     float hi) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::string path = file_of(dir, key), tmp = fmt::format("{}.{}.tmp", path, getpid());
  {
    std::ofstream f(tmp, std::ios::binary);
    f << kMagic << '\n' << key << '\n';
    const float range[2] = {lo, hi};
    f.write(reinterpret_cast<const char*>(range), sizeof range);
    for (const auto& v : in.bound)
      f.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
    if (!f) {
      fmt::print(stderr, "terrasprite: warning: {}: cannot cache the bounds of {} there\n", dir,
                 in.path);
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace terrasprite
