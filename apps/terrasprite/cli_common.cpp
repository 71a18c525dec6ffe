// SPDX-License-Identifier: MIT
#include "cli_common.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string_view>

#include "terrasprite/common/error.h"
#include "terrasprite/output/output_dir.h"

namespace terrasprite::cli {

std::string with_option_names(const std::string& message) {
  // Value names of the library's options structs -> the CLI options that set them.
  static const std::pair<const char*, const char*> kNames[] = {
      {"dem", "--dem"},
      {"synthetic_size", "--synthetic-size"},
      {"erosion_passes", "--erosion"},
      {"z_scale", "--z-scale"},
      {"exaggeration", "--exaggeration"},
      {"spacing_m", "--spacing"},
      {"resample", "--resample"},
      {"frames", "--frames"},
      {"lod_quads", "--lod-quads"},
      {"threshold_px", "--threshold"},
      {"pixel_voxel_ratio", "--pixel-voxel-ratio"},
  };
  for (const auto& [value, option] : kNames) {
    const std::string prefix = std::string(value) + " ";
    if (message.rfind(prefix, 0) == 0) return option + message.substr(std::string(value).size());
  }
  return message;
}

void add_terrain_options(CLI::App& cmd, TerrainOptions& o) {
  cmd.add_option_function<std::string>(
      "--dem",
      [&o](const std::string& f) {
        o.dem = f;
        o.dem_given = true;
      },
      "height raster (GeoTIFF, .hgt, 16-bit PNG, terrain-RGB, ...); default: synthetic");
  cmd.add_option("--texture", o.texture, "drape texture file, 'checker' or 'derived' (default)");
  cmd.add_option("--z-scale", o.z_scale, "multiply raw height samples (e.g. 0.1 for decimetres)");
  cmd.add_option("--spacing", o.spacing, "sample spacing in metres (overrides the file's)");
  cmd.add_option("--nodata", o.nodata, "nodata value for rasters that do not tag one");
  add_fill_option(cmd, o);
  cmd.add_option_function<std::string>(
         "--encoding",
         [&o](const std::string& e) {
           o.encoding = e == "terrain-rgb" ? HeightEncoding::kTerrainRgb
                        : e == "terrarium" ? HeightEncoding::kTerrarium
                                           : HeightEncoding::kAuto;
         },
         "RGB height encoding: auto|terrain-rgb|terrarium")
      ->check(CLI::IsMember({"auto", "terrain-rgb", "terrarium"}));
  cmd.add_option("--exaggeration", o.exaggeration, "vertical exaggeration for display (default 1)");
  cmd.add_option("--resample", o.resample,
                 "resample heights to N x N samples (e.g. 513 for the paper setup)");
  cmd.add_option("--seed", o.seed, "synthetic terrain seed");
  cmd.add_option("--synthetic-size", o.synthetic_size,
                 "synthetic terrain samples per side, 2..8193 (default 513)");
  cmd.add_option("--erosion", o.erosion_passes,
                 "synthetic terrain erosion passes, 0..100 (default 2)");
}

void add_fill_option(CLI::App& cmd, TerrainOptions& o) {
  // Holes are only described: every other command draws or writes whole heights.
  const bool holes_ok = cmd.get_name() == "info";
  cmd.add_option_function<std::string>(
         "--fill",
         [&o, holes_ok](const std::string& f) {
           if (f == "none" && !holes_ok)
             throw InputError(
                 "--fill none: only info takes it; the renderers (GL and voxel) draw no holes "
                 "and tile writes whole heights (use --fill amle or gdal, and --show-voids to see "
                 "the filled cells)");
           o.fill = f == "gdal"   ? NodataFill::kGdal
                    : f == "none" ? NodataFill::kNone
                                  : NodataFill::kAmle;
         },
         "how nodata cells (voids) are filled: amle (default; least steep surface from the rim), "
         "gdal (GDALFillNodata, inverse distance) or none (info only: the voids stay holes)")
      ->check(CLI::IsMember({"amle", "gdal", "none"}));
}

void add_show_voids_option(CLI::App& cmd, TerrainOptions& o) {
  cmd.add_flag("--show-voids", o.show_voids,
               "tint the terrain magenta where the DEM had nodata cells (filled by --fill)");
}

Terrain load_terrain_verbose(const TerrainOptions& o) {
  std::vector<std::string> warnings;
  Terrain t = load_terrain(o, &warnings);
  for (const auto& w : warnings) fmt::print(stderr, "warning: {}\n", w);
  return t;
}

std::pair<int, int> parse_size(const std::string& text, const char* option) {
  // Whole digits parsed into 64 bits and range-checked: "4294967360x64" must not wrap to 64x64.
  auto number = [&](std::string_view part) -> long long {
    long long v = 0;
    const bool sign = !part.empty() && part[0] == '-';
    const auto digits = part.substr(sign ? 1 : 0);
    auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (digits.empty() || end != digits.data() + digits.size())
      throw InputError(fmt::format("{} {}: expected WIDTHxHEIGHT, e.g. 512x512", option, text));
    if (ec == std::errc::result_out_of_range) v = std::numeric_limits<long long>::max();
    return sign ? -v : v;
  };
  const std::size_t x = text.find_first_of("xX");
  if (x == std::string::npos)
    throw InputError(fmt::format("{} {}: expected WIDTHxHEIGHT, e.g. 512x512", option, text));
  const long long w = number(std::string_view(text).substr(0, x)),
                  h = number(std::string_view(text).substr(x + 1));
  if (w <= 0 || h <= 0 || w > 16384 || h > 16384)
    throw InputError(
        fmt::format("{} {}: width and height must be between 1 and 16384", option, text));
  return {int(w), int(h)};
}

void check_lod_quads(int quads, const Heightfield& h, const char* option) {
  const int most = std::min(h.width, h.height) - 1;
  if (quads < 1 || quads > most)
    throw InputError(fmt::format("{} {}: must be between 1 and {} for the {}x{}-sample terrain",
                                 option, quads, most, h.width, h.height));
}

void require_finite_numbers(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end != text.c_str() && !std::isfinite(v)) return text + " is not a finite number";
        return {};
      },
      "", "finite");
  for (CLI::Option* opt : app.get_options())
    if (opt->get_type_name().rfind("FLOAT", 0) == 0) opt->check(finite);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    require_finite_numbers(*sub);
}

std::vector<double> parse_list(const std::string& text, const char* option) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v))
      throw InputError(fmt::format("{} {}: expected comma-separated numbers", option, text));
    out.push_back(v);
  }
  if (out.empty()) throw InputError(fmt::format("{}: empty list", option));
  return out;
}

std::vector<int> int_list(const std::string& text, const char* option) {
  std::vector<int> out;
  for (double v : parse_list(text, option)) {
    if (v != std::floor(v) || v <= 0 || v > std::numeric_limits<int>::max())
      throw InputError(fmt::format("{}: {} is not a positive whole number", option, v));
    out.push_back(int(v));
  }
  return out;
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
  return out;
}

void check_outputs(const OutputPolicy& policy, const std::string& out_dir,
                   std::initializer_list<std::string> files) {
  if (!out_dir.empty()) OutputDir::check(out_dir, policy);
  for (const std::string& f : files)
    if (!f.empty()) check_output_file(f, policy);
}

Progress::Progress(std::string label)
    : label_(std::move(label)), tty_(isatty(STDERR_FILENO) == 1) {}

void Progress::operator()(int done, int total) {
  if (!tty_ || total <= 0) return;
  const int width = 30, fill = done * width / total;
  fmt::print(stderr, "\r{} [{}{}] {}/{}", label_, std::string(fill, '#'),
             std::string(width - fill, '.'), done, total);
  drawn_ = true;
}

Progress::~Progress() {
  if (drawn_) fmt::print(stderr, "\n");
}

std::function<void(const char*, int, int)> stage_progress(std::string label) {
  struct Bar {
    std::string stage;
    std::unique_ptr<Progress> bar;
  };
  auto state = std::make_shared<Bar>();
  return [label = std::move(label), state](const char* stage, int done, int total) {
    if (!state->bar || state->stage != stage) {
      state->bar.reset();  // ends the previous stage's line
      state->stage = stage;
      state->bar = std::make_unique<Progress>(label + " " + stage);
    }
    (*state->bar)(done, total);
  };
}

CLI::Option* add_path_option(CLI::App& cmd, std::string& path, const std::string& default_text) {
  return cmd.add_option("--path", path,
                        fmt::format("camera path: {} | a JSON path file (default {})", kPathChoices,
                                    default_text.empty() ? path : default_text));
}

void print_bench_result(const nlohmann::json& j, const std::string& json_file,
                        const std::string& summary) {
  if (json_file.empty()) {  // the same object --json would write, generator included
    nlohmann::json with_generator = j;
    with_generator["generator"] = generator_name();
    fmt::print("{}\n", with_generator.dump(2));
    return;
  }
  fmt::print("{}JSON: {}\n", summary, json_file);
}

}  // namespace terrasprite::cli
