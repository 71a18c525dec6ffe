// SPDX-License-Identifier: MIT
// The on-disk cache of quality tables (shared by `objects table` and `bench hybrid`).
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <optional>

#include "objects_table.h"

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
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream f(tmp);
    f << j.dump();
    if (!f) {
      fmt::print(stderr, "warning: cannot write the cache file {}\n", file.string());
      return;
    }
  }
  std::filesystem::rename(tmp, file, ec);
}

std::filesystem::path table_cache_file(const std::string& cache_dir, const std::string& model_file,
                                       const ModelOptions& m, const TableOptions& o) {
  return std::filesystem::path(cache_dir.empty() ? default_cache_dir() : cache_dir) /
         (std::filesystem::path(model_file).stem().string() + "-" +
          table_cache_key(model_file, m, o) + ".json");
}

}  // namespace terrasprite::cli
