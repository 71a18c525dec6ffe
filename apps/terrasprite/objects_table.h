// SPDX-License-Identifier: MIT
// `objects table`: the measured quality table of one model, its on-disk
// cache, its JSON and its report (plots of the paper's Figures 1-3, Table 1).
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/objects/model.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/objects/quality_table.h"
#include "terrasprite/objects/representation_cache.h"

namespace terrasprite::cli {

/// The table as the JSON contract has it (model, triangles, representations, table).
nlohmann::json table_json(const QualityTable& t, const TableOptions& o);
/// Reads back what table_json wrote (for the cache). Throws InputError on a
/// document that does not have the expected shape.
QualityTable table_from_json(const nlohmann::json& j);

/// Cache key of a table: model_source_key() (the model file's bytes, its
/// texture's and the model options), then a hash of the table options, the
/// LOD chain's key (lod_chain_key: levels built otherwise make another
/// table) and the format version; 48 hex digits.
std::string table_cache_key(const std::string& model_file, const ModelOptions& m,
                            const TableOptions& o, const std::string& chain);
/// The cache file of a model's table in `cache_dir` (empty: default_cache_dir()).
std::filesystem::path table_cache_file(const std::string& cache_dir, const std::string& model_file,
                                       const ModelOptions& m, const TableOptions& o,
                                       const std::string& chain);
/// The cached table in `file`, if one is there and readable (an unreadable
/// one is reported on stderr and ignored).
std::optional<QualityTable> read_table_cache(const std::filesystem::path& file);
/// Stores `j` (table_json) atomically; a failure is a warning, not an error.
void write_table_cache(const std::filesystem::path& file, const nlohmann::json& j);
/// {hits, misses, rejected, read_ms, build_ms} of the representation cache.
nlohmann::json cache_stats_json(const RepresentationCacheStats& s);

/// Writes the .dat files, plots (gnuplot; skipped with a note when missing),
/// and table1.md into `out`.
void write_objects_report(const QualityTable& t, const TableOptions& o, OutputDir& out);

/// A comma-separated list of positive whole numbers (`option` names it in errors).
std::vector<int> int_list(const std::string& text, const char* option);

/// Table 1 as Markdown text (also printed by the command).
std::string table1_markdown(const QualityTable& t, const TableOptions& o);

}  // namespace terrasprite::cli
