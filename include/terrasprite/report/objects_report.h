// SPDX-License-Identifier: MIT
// The objects commands' outputs: a model's description (`objects info`), a
// quality table's JSON, .dat files, gnuplot plots of the paper's Figures 1-3
// and Table 1 (`objects table`), and a scene's frame and figures
// (`objects scene`).
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "terrasprite/experiment/objects/full_geometry.h"
#include "terrasprite/experiment/objects/objects_table.h"
#include "terrasprite/objects/model.h"
#include "terrasprite/output/output_dir.h"

namespace terrasprite::report {

/// model, triangles, vertices, parts, materials, normals ("file" or
/// "computed"), scale_to_m, bounds_min_m, bounds_max_m, bounding_radius_m,
/// textures ({name, size}).
nlohmann::json model_info_json(const Model& model);

/// {hits, misses, rejected, read_ms, build_ms} of a representation cache.
nlohmann::json cache_stats_json(const RepresentationCacheStats& s);

/// The table's JSON (table_json) with `cached` and `representation_cache`.
nlohmann::json objects_table_json(const ObjectsTableResult& r, const TableOptions& o);

/// Table 1 as Markdown text (also printed by the command).
std::string table1_markdown(const QualityTable& t, const TableOptions& o);

/// Writes the .dat files, plots.gp and its plots (gnuplot; skipped with a
/// warning on stderr when it fails) and table1.md into `out`.
void write_objects_report(const QualityTable& t, const TableOptions& o, OutputDir& out);

/// What in the report would come out degenerate with these options, one
/// line each (empty when nothing): views too few for fig1's heat maps to be
/// a surface, a single size (fig2's lines are points).
std::vector<std::string> objects_report_warnings(const TableOptions& o);

/// `objects table`'s files: write_objects_report's, table.json in `out`
/// and, unless `json_path` is empty, the same JSON there.
void write_objects_table(const ObjectsTableResult& r, const TableOptions& o, OutputDir& out,
                         const std::string& json_path, const OutputPolicy& policy);

/// gl_renderer, size, instances, load_ms, representation_cache,
/// full_triangles, terrain_triangles, frame_triangles, frames, median_ms,
/// terrain_median_ms, models ({name, file, triangles, instances, lod_levels}).
nlohmann::json full_geometry_json(const FullGeometryResult& r);

/// `objects scene`'s files: frame.png and scene.json in `out` and, unless
/// `json_path` is empty, the same JSON there.
void write_full_geometry(const FullGeometryResult& r, OutputDir& out, const std::string& json_path,
                         const OutputPolicy& policy);

}  // namespace terrasprite::report
