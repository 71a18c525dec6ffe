// SPDX-License-Identifier: MIT
// The on-disk cache of quality tables.
#include "terrasprite/objects/quality_table_cache.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "terrasprite/objects/quality_table_json.h"
#include "terrasprite/objects/representation_cache.h"

namespace terrasprite {

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

std::string table_cache_key(const std::string& model_file, const ModelOptions& m,
                            const TableOptions& o, const std::string& chain) {
  // The model and its options as the representation cache keys them (files,
  // axes, size, texture, colour, faces), then what the table measures.
  std::string params = fmt::format("{}|{}|", kQualityTableFormat, chain);
  for (ObjectKind k : o.kinds) params += object_kind_name(k) + std::string(",");
  params += fmt::format("|r{}|s{}|a{}|fs{}|v{}|n{}|t{}|{}", fmt::join(o.resolutions, ","),
                        fmt::join(o.sizes_px, ","), o.angle_step_deg, o.full_sphere, o.views,
                        o.timing_instances, fmt::join(o.ssim_targets, ","),
                        fmt::join(o.psnr_targets, ","));
  // Samples and headings are keyed only when not the defaults (1, {0}), so
  // a table at the defaults keeps the key it has always had.
  if (o.samples > 1) params += fmt::format("|ms{}", o.samples);
  if (o.headings_deg != std::vector<double>{0.0})
    params += fmt::format("|h{}", fmt::join(o.headings_deg, ","));
  return model_source_key(model_file, m) + fmt::format("{:016x}", fnv1a(params));
}

std::filesystem::path table_cache_file(const std::string& cache_dir, const std::string& model_file,
                                       const ModelOptions& m, const TableOptions& o,
                                       const std::string& chain) {
  return std::filesystem::path(cache_dir.empty() ? default_cache_dir() : cache_dir) /
         (std::filesystem::path(model_file).stem().string() + "-" +
          table_cache_key(model_file, m, o, chain) + ".json");
}

}  // namespace terrasprite
