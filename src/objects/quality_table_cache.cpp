// SPDX-License-Identifier: MIT
// The on-disk cache of quality tables.
#include "terrasprite/objects/quality_table_cache.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include "terrasprite/common/cache_entry.h"
#include "terrasprite/objects/quality_table_json.h"
#include "terrasprite/objects/representation_cache.h"
#include "terrasprite/output/atomic_file.h"

namespace terrasprite {
namespace {

// A table's JSON is a few hundred kilobytes at most: an entry claiming more
// is damaged and is not decoded.
constexpr std::uint64_t kMaxTableBytes = std::uint64_t(64) << 20;

/// Every table option, readable (the entry records it whole).
std::string table_params(const TableOptions& o, const std::string& chain) {
  std::string params = fmt::format("{}|{}|", kQualityTableFormat, chain);
  for (ObjectKind k : o.kinds) params += object_kind_name(k) + std::string(",");
  params += fmt::format("|r{}|s{}|a{}|fs{}|v{}|n{}|t{}|{}|ms{}|h{}", fmt::join(o.resolutions, ","),
                        fmt::join(o.sizes_px, ","), o.angle_step_deg, o.full_sphere, o.views,
                        o.timing_instances, fmt::join(o.ssim_targets, ","),
                        fmt::join(o.psnr_targets, ","), o.samples, fmt::join(o.headings_deg, ","));
  return params;
}

}  // namespace

TableCacheEntry table_cache_entry(const std::string& cache_dir, const std::string& model_file,
                                  const Model& model, const ModelOptions& m, const TableOptions& o,
                                  const std::string& chain) {
  const std::string source = model_source_key(model, m), params = table_params(o, chain);
  TableCacheEntry e;
  e.file = std::filesystem::path(cache_dir.empty() ? default_cache_dir() : cache_dir) /
           fmt::format("{}-{}{:016x}.table", std::filesystem::path(model_file).stem().string(),
                       source, fnv1a(params));
  e.key = fmt::format("terrasprite quality table of {} {}", source, params);
  return e;
}

std::optional<QualityTable> read_table_cache(const TableCacheEntry& entry) {
  CacheEntryRead r = read_cache_entry(entry.file, entry.key, kMaxTableBytes);
  if (r.payload) {
    try {
      return table_from_json(nlohmann::json::parse(*r.payload));
    } catch (const std::exception& e) {
      r.problem = e.what();
    }
  }
  if (!r.problem.empty())
    fmt::print(stderr, "warning: ignoring the cache entry {}: {}; measuring it again\n",
               entry.file.string(), r.problem);
  return std::nullopt;
}

void write_table_cache(const TableCacheEntry& entry, const nlohmann::json& j) {
  const std::string bytes = encode_cache_entry(entry.key, j.dump());
  if (bytes.empty() || !replace_file_atomically(entry.file, bytes))
    fmt::print(stderr, "warning: cannot write the cache entry {}\n", entry.file.string());
}

}  // namespace terrasprite
