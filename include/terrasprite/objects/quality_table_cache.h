// SPDX-License-Identifier: MIT
// The on-disk cache of quality tables (`objects table`, `bench hybrid`): one
// cache entry (terrasprite/common/cache_entry.h) per model, options and LOD
// chain, holding the table as JSON (quality_table_json.h).
#pragma once
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "terrasprite/objects/model.h"
#include "terrasprite/objects/quality_table.h"

namespace terrasprite {

/// Where a table is cached and the key its entry records.
struct TableCacheEntry {
  /// `<cache_dir>/<model stem>-<48 hex digits>.table`: where to look.
  std::filesystem::path file;
  /// What the entry must record to be read: the format version,
  /// model_source_key() (the loaded model's content and its options), the
  /// LOD chain's key (lod_chain_key: levels built otherwise make another
  /// table) and every table option.
  std::string key;
};

/// The entry of the table measured on `model` (loaded from `model_file` with
/// `m`) with `o` on the chain `chain`, in `cache_dir` (empty: default_cache_dir()).
TableCacheEntry table_cache_entry(const std::string& cache_dir, const std::string& model_file,
                                  const Model& model, const ModelOptions& m, const TableOptions& o,
                                  const std::string& chain);

/// The cached table, if an entry of this key is there, intact and readable;
/// a present but unusable one is a note on stderr (one line) and a miss.
std::optional<QualityTable> read_table_cache(const TableCacheEntry& entry);

/// Stores `j` (table_json) atomically; a failure is a warning on stderr, not an error.
void write_table_cache(const TableCacheEntry& entry, const nlohmann::json& j);

}  // namespace terrasprite
