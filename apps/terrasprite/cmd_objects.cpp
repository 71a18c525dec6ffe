// SPDX-License-Identifier: MIT
// terrasprite objects: load a model (info), build its representations and
// measure their quality tables (table).
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "objects_table.h"
#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/model.h"
#include "terrasprite/objects/object_renderer.h"

namespace terrasprite::cli {
namespace {

struct ModelArgs {
  std::string file;
  std::string up = "y";
  double height_m = 0.0;
  std::string texture;
};

void add_model_options(CLI::App& cmd, ModelArgs& m) {
  cmd.add_option("--model", m.file, "model file: .obj, .gltf or .glb")->required();
  cmd.add_option("--up", m.up, "the file's up axis: y or z")->capture_default_str();
  cmd.add_option("--height-m", m.height_m, "real height in metres (0 keeps file units)")
      ->check(CLI::NonNegativeNumber);
  cmd.add_option("--texture", m.texture, "texture for a model without materials (image file)");
}

ModelOptions model_options(const ModelArgs& m) {
  ModelOptions o;
  o.up = parse_up_axis(m.up, "--up");
  o.height_m = m.height_m;
  o.texture = m.texture;
  return o;
}

Model load(const ModelArgs& m) {
  return load_model(m.file, model_options(m));
}

void add_objects_info(CLI::App& objects) {
  auto* cmd =
      objects.add_subcommand("info", "describe a model: triangles, vertices, bounds, textures");
  auto m = std::make_shared<ModelArgs>();
  auto json = std::make_shared<std::string>();
  add_model_options(*cmd, *m);
  cmd->add_option("--json", *json, "write the description as JSON");
  cmd->callback([m, json] {
    check_outputs("", {*json});
    const Model model = load(*m);
    nlohmann::json textures = nlohmann::json::array();
    for (std::size_t i = 0; i < model.textures.size(); ++i)
      textures.push_back({{"name", model.texture_names[i]},
                          {"size", {model.textures[i].width, model.textures[i].height}}});
    const glm::vec3 lo = model.bounds_min, hi = model.bounds_max;
    nlohmann::json j = {{"model", model.name},
                        {"triangles", model.triangles()},
                        {"vertices", model.vertices()},
                        {"parts", model.parts.size()},
                        {"materials", model.materials.size()},
                        {"normals", model.normals_from_file ? "file" : "computed"},
                        {"scale_to_m", model.scale_to_m},
                        {"bounds_min_m", {lo.x, lo.y, lo.z}},
                        {"bounds_max_m", {hi.x, hi.y, hi.z}},
                        {"bounding_radius_m", model.bounding_radius()},
                        {"textures", textures}};
    if (!json->empty()) write_json(j, *json);
    fmt::print("{}: {} triangles, {} vertices, {} parts, normals {}\n", model.name,
               model.triangles(), model.vertices(), model.parts.size(),
               model.normals_from_file ? "from the file" : "computed");
    fmt::print("bounds {:.3f} x {:.3f} x {:.3f} m (scale {:.4g} m per file unit)\n", hi.x - lo.x,
               hi.y - lo.y, hi.z - lo.z, model.scale_to_m);
    for (std::size_t i = 0; i < model.textures.size(); ++i)
      fmt::print("texture {}: {} x {}\n", model.texture_names[i], model.textures[i].width,
                 model.textures[i].height);
  });
}

struct TableArgs {
  ModelArgs model;
  std::string kinds = "pm,relief,octahedral";
  std::string resolutions = "16,32,64,128,256,512";
  std::string sizes = "400,200,100,50,25";
  double angle_step = 30.0;
  std::string headings = "0";
  bool full_sphere = false;
  int views = 12;
  std::string json, out, cache;
  bool no_cache = false;
};

TableOptions table_options(const TableArgs& a) {
  TableOptions o;
  o.kinds.clear();
  std::stringstream ss(a.kinds);
  for (std::string k; std::getline(ss, k, ',');) o.kinds.push_back(parse_object_kind(k, "--kinds"));
  o.resolutions = int_list(a.resolutions, "--resolutions");
  o.sizes_px = int_list(a.sizes, "--sizes-px");
  o.angle_step_deg = a.angle_step;
  o.full_sphere = a.full_sphere;
  o.headings_deg = parse_list(a.headings, "--headings");
  check_headings(o.headings_deg, "--headings");
  o.views = a.views;
  for (int r : o.resolutions)
    if (r < 16 || r > 512) throw InputError(fmt::format("--resolutions: {} is outside 16..512", r));
  if (o.views < 2 || o.views > 32)
    throw InputError(fmt::format("--views: {} is outside 2..32", o.views));
  return o;
}

/// `cache` holds the representations (a disabled one: all built here).
QualityTable measure(const Model& model, const TableOptions& o, const RepresentationCache& cache) {
  GlContext ctx;
  GlModel gl_model(model, cached_lod_chain(model, LodOptions{}, cache), cache);
  Progress progress("objects table");
  return measure_quality_table(gl_model, o, [&](int done, int total) { progress(done, total); });
}

void add_objects_table(CLI::App& objects) {
  auto* cmd = objects.add_subcommand(
      "table", "measure a model's representations against it: quality tables, plots, Table 1");
  auto a = std::make_shared<TableArgs>();
  add_model_options(*cmd, a->model);
  cmd->add_option("--kinds", a->kinds, "representations: pm,relief,octahedral")
      ->capture_default_str();
  cmd->add_option("--resolutions", a->resolutions, "impostor resolutions (16..512)")
      ->capture_default_str();
  cmd->add_option("--sizes-px", a->sizes, "on-screen bounding-sphere diameters")
      ->capture_default_str();
  cmd->add_option("--angle-step", a->angle_step, "degrees between sampled views")
      ->capture_default_str();
  cmd->add_flag("--full-sphere", a->full_sphere, "theta 0..180 (views from below too)");
  cmd->add_option("--headings", a->headings,
                  "model headings, degrees in [0, 360): the sun's side of the model")
      ->capture_default_str();
  cmd->add_option("--views", a->views, "octahedral views per side")->capture_default_str();
  cmd->add_option("--json", a->json, "write the table as JSON");
  cmd->add_option("--out", a->out, "report directory (plots, Table 1)")->capture_default_str();
  cmd->add_option("--cache", a->cache, "cache directory (default: ~/.cache/terrasprite/objects)");
  cmd->add_flag("--no-cache", a->no_cache,
                "build the representations and measure again; read and store nothing");
  cmd->callback([a] {
    const TableOptions o = table_options(*a);
    const ModelOptions mo = model_options(a->model);
    const std::string stem = std::filesystem::path(a->model.file).stem().string();
    const std::string out_dir = a->out.empty() ? "out/objects_" + stem : a->out;
    check_outputs(out_dir, {a->json});
    const Model model = load_model(a->model.file, mo);
    OutputDir out(out_dir, output_policy());
    const std::filesystem::path cache_file =
        table_cache_file(a->cache, a->model.file, mo, o, lod_chain_key(LodOptions{}));
    std::optional<QualityTable> t = a->no_cache ? std::nullopt : read_table_cache(cache_file);
    const bool cached = t.has_value();
    const RepresentationCache reps =
        a->no_cache ? RepresentationCache{}
                    : RepresentationCache(a->cache.empty() ? default_cache_dir() : a->cache,
                                          model_source_key(a->model.file, mo),
                                          std::filesystem::path(a->model.file).stem().string());
    if (!cached) t = measure(model, o, reps);
    nlohmann::json j = table_json(*t, o);
    if (!cached && !a->no_cache) write_table_cache(cache_file, j);
    j["cached"] = cached;
    j["representation_cache"] = cache_stats_json(reps.stats());
    write_objects_report(*t, o, out);
    write_json(j, out.file("table.json"));
    if (!a->json.empty()) write_json(j, a->json);
    out.commit();
    fmt::print("{}", table1_markdown(*t, o));
    fmt::print("\n{} representations, {} samples each; {} in {:.1f} s\n", t->representations.size(),
               t->representations.empty() ? 0 : t->representations[0].samples.size(),
               cached ? "read from the cache, first measured" : "measured", t->build_ms / 1000.0);
    if (cached) fmt::print("cache: {}\n", cache_file.string());
  });
}

}  // namespace

std::vector<int> int_list(const std::string& text, const char* option) {
  std::vector<int> out;
  for (double v : parse_list(text, option)) {
    if (v != std::floor(v) || v <= 0)
      throw InputError(fmt::format("{}: {} is not a positive whole number", option, v));
    out.push_back(int(v));
  }
  return out;
}

void add_objects_scene(CLI::App& objects);  // objects_scene.cpp

void add_objects(CLI::App& app) {
  auto* objects =
      app.add_subcommand("objects", "object models: info, representations, quality tables");
  objects->require_subcommand(1);
  add_objects_info(*objects);
  add_objects_table(*objects);
  add_objects_scene(*objects);
}

}  // namespace terrasprite::cli
