// SPDX-License-Identifier: MIT
// Options and helpers shared by the sub-commands.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "terrasprite/output/output_file.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/report/terrain_json.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite::cli {

/// The library names values as its options structs do ("lod_quads 0: must
/// be at least 1"); a message that starts with such a name gets the CLI
/// option that sets it instead ("--lod-quads 0: ..."). Others pass unchanged.
std::string with_option_names(const std::string& library_message);

/// --dem --texture --z-scale --spacing --nodata --encoding --exaggeration
/// --resample --seed --synthetic-size --erosion
void add_terrain_options(CLI::App& cmd, TerrainOptions& o);

/// --fill amle|gdal|none (part of add_terrain_options); none is refused
/// (InputError) except by `info`: no renderer draws holes.
void add_fill_option(CLI::App& cmd, TerrainOptions& o);
/// --show-voids, for the commands that draw the terrain.
void add_show_voids_option(CLI::App& cmd, TerrainOptions& o);

/// Loads the terrain, printing loader warnings on stderr (one line each).
Terrain load_terrain_verbose(const TerrainOptions& o);

/// Every floating-point option of `app` and its sub-commands (at any depth)
/// refuses NaN and infinities ("--tolerance: nan is not a finite number"):
/// CLI11 parses them as numbers and its Range checks let NaN through. Call
/// once, after every option is added.
void require_finite_numbers(CLI::App& app);

/// "WxH" -> {w, h}; throws InputError naming `option` for a zero, negative,
/// absurd (> 16384) or malformed size.
std::pair<int, int> parse_size(const std::string& text, const char* option);

/// Throws InputError naming `option` unless 1 <= quads <= the terrain's
/// quads along its shorter side (a coarser grid than that is not a LOD; a
/// finer one would be clamped silently).
void check_lod_quads(int quads, const Heightfield& h, const char* option = "--lod-quads");

/// Comma-separated list of numbers; throws InputError naming `option`.
std::vector<double> parse_list(const std::string& text, const char* option);
/// A comma-separated list of positive whole numbers (`option` names it in errors).
std::vector<int> int_list(const std::string& text, const char* option);
/// Comma-separated list of words, as written (empty text: none).
std::vector<std::string> split_list(const std::string& text);

/// Checks, before any work, that every output can be written under `policy`:
/// the output directory `out_dir` (skipped when empty) and each non-empty file
/// name. Throws InputError naming the first that cannot.
void check_outputs(const OutputPolicy& policy, const std::string& out_dir,
                   std::initializer_list<std::string> files);

/// The built-in camera paths every --path takes besides a JSON path file.
inline constexpr const char* kPathChoices =
    "'overview' (the paper's flight, brought closer over terrain flatter than the synthetic "
    "one) | 'paper' (the LOD-sprite paper's flight) | 'low-fast' (low and fast over the terrain)";

/// --path, defined once for every command that flies a path: a built-in path
/// (kPathChoices) or a JSON path file. The help shows `default_text`, or
/// `path`'s value when that is empty.
CLI::Option* add_path_option(CLI::App& cmd, std::string& path,
                             const std::string& default_text = "");

/// A bench's result on stdout: with no --json file (`json_file` empty), the
/// JSON `j` itself (the contract scripts read); with one, the short human
/// `summary` and where the JSON went.
void print_bench_result(const nlohmann::json& j, const std::string& json_file,
                        const std::string& summary);

using report::number_or_null;
using report::run_gnuplot;
using report::write_text;

using report::terrain_json;

/// A progress callback for a study that runs in stages: one Progress bar per
/// stage, labelled "`label` STAGE", ended when the next stage starts.
std::function<void(const char* stage, int done, int total)> stage_progress(std::string label);

/// A one-line progress bar on stderr, drawn only when stderr is a terminal.
class Progress {
 public:
  explicit Progress(std::string label);
  void operator()(int done, int total);
  ~Progress();

 private:
  std::string label_;
  bool tty_;
  bool drawn_ = false;
};

}  // namespace terrasprite::cli
