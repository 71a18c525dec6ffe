// SPDX-License-Identifier: MIT
// The on-disk cache of quality tables (shared by `objects table` and `bench hybrid`).
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <optional>

#include "objects_table.h"
#include "terrasprite/objects/representation_cache.h"

namespace terrasprite::cli {

// The cached table for `key`, if one is there and readable.
std::optional<QualityTable> read_table_cache(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    return table_from_json(nlohmann::json::parse(in));
  } catch (const std::exception& e) {
    fmt::print(stderr, "warning: ignoring unreadable cache file {}: {}\n", file.string(), e.what());
    return std::nullopt;
  }
}

void write_table_cache(const std::filesystem::path& file, const nlohmann::json& j) {
  if (!write_file_atomically(file, j.dump()))
    fmt::print(stderr, "warning: cannot write the cache file {}\n", file.string());
}

nlohmann::json cache_stats_json(const RepresentationCacheStats& s) {
  return {{"hits", s.hits},
          {"misses", s.misses},
          {"rejected", s.rejected},
          {"read_ms", s.read_ms},
          {"build_ms", s.build_ms}};
}

std::filesystem::path table_cache_file(const std::string& cache_dir, const std::string& model_file,
                                       const ModelOptions& m, const TableOptions& o,
                                       const std::string& chain) {
  return std::filesystem::path(cache_dir.empty() ? default_cache_dir() : cache_dir) /
         (std::filesystem::path(model_file).stem().string() + "-" +
          table_cache_key(model_file, m, o, chain) + ".json");
}

}  // namespace terrasprite::cli
