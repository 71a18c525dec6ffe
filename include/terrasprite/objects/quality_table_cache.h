// SPDX-License-Identifier: MIT
// The on-disk cache of quality tables (`objects table`, `bench hybrid`): one
// JSON file (quality_table_json.h) per model, options and LOD chain.
#pragma once
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "terrasprite/objects/model.h"
#include "terrasprite/objects/quality_table.h"

namespace terrasprite {

/// Cache key of a table: model_source_key() (the model file's bytes, its
/// texture's and the model options), then a hash of the table options, the
/// LOD chain's key (lod_chain_key: levels built otherwise make another
/// table) and the format version; 48 hex digits. Throws InputError when the
/// model file cannot be read.
std::string table_cache_key(const std::string& model_file, const ModelOptions& m,
                            const TableOptions& o, const std::string& chain);

/// The cache file of a model's table in `cache_dir` (empty: default_cache_dir()):
/// `<model stem>-<table_cache_key>.json`.
std::filesystem::path table_cache_file(const std::string& cache_dir, const std::string& model_file,
                                       const ModelOptions& m, const TableOptions& o,
                                       const std::string& chain);

/// The cached table in `file`, if one is there and readable (an unreadable
/// one is reported on stderr and ignored).
std::optional<QualityTable> read_table_cache(const std::filesystem::path& file);

/// Stores `j` (table_json) atomically; a failure is a warning on stderr, not an error.
void write_table_cache(const std::filesystem::path& file, const nlohmann::json& j);

}  // namespace terrasprite
