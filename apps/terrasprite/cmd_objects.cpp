// SPDX-License-Identifier: MIT
// terrasprite objects: describe a model (info), measure its representations'
// quality tables (table), time a scene's objects at full geometry (scene).
#include <fmt/format.h>

#include <filesystem>
#include <sstream>
#include <tuple>

#include "cli_common.h"
#include "commands.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/objects/full_geometry.h"
#include "terrasprite/experiment/objects/objects_table.h"
#include "terrasprite/objects/attach_objects.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/objects_report.h"
#include "terrasprite/terrain/geo_frame.h"

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
  cmd.add_option("--height-m", m.height_m, "real height in metres, 0..10000 (0 keeps file units)");
  cmd.add_option("--texture", m.texture, "texture for a model without materials (image file)");
}

ModelOptions model_options(const ModelArgs& m) {
  ModelOptions o;
  o.up = parse_up_axis(m.up, "--up");
  o.height_m = m.height_m;
  check_model_options(o, "--height-m");
  o.texture = m.texture;
  return o;
}

Model load(const ModelArgs& m) {
  return load_model(m.file, model_options(m));
}

void add_objects_info(CLI::App& objects, const OutputPolicy& policy) {
  auto* cmd =
      objects.add_subcommand("info", "describe a model: triangles, vertices, bounds, textures");
  auto m = std::make_shared<ModelArgs>();
  auto json = std::make_shared<std::string>();
  add_model_options(*cmd, *m);
  cmd->add_option("--json", *json, "write the description as JSON");
  cmd->callback([m, json, &policy] {
    check_outputs(policy, "", {*json});
    const Model model = load(*m);
    const nlohmann::json j = report::model_info_json(model);
    const glm::vec3 lo = model.bounds_min, hi = model.bounds_max;
    if (!json->empty()) report::write_json(j, *json, policy);
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

void add_objects_table(CLI::App& objects, const OutputPolicy& policy) {
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
  cmd->callback([a, &policy] {
    ObjectsTableOptions o;
    o.table = table_options(*a);
    o.model_file = a->model.file;
    o.model = model_options(a->model);
    o.cache_dir = a->cache;
    o.use_cache = !a->no_cache;
    const std::string stem = std::filesystem::path(a->model.file).stem().string();
    const std::string out_dir = a->out.empty() ? "out/objects_" + stem : a->out;
    check_outputs(policy, out_dir, {a->json});
    for (const std::string& w : report::objects_report_warnings(o.table))
      fmt::print(stderr, "warning: {}\n", w);
    Progress progress("objects table");
    o.progress = [&](int done, int total) { progress(done, total); };
    const ObjectsTableResult r = run_objects_table(o);
    OutputDir out(out_dir, policy);
    report::write_objects_table(r, o.table, out, a->json, policy);
    out.commit();
    const QualityTable& t = r.table;
    fmt::print("{}", report::table1_markdown(t, o.table));
    fmt::print("\n{} representations, {} samples each; {} in {:.1f} s\n", t.representations.size(),
               t.representations.empty() ? 0 : t.representations[0].samples.size(),
               r.cached ? "read from the cache, first measured" : "measured", t.build_ms / 1000.0);
    if (r.cached) fmt::print("cache: {}\n", r.cache_file.string());
  });
}

// The view `objects scene` chose, and where the placed instances were written.
void print_scene_camera(const Camera& c, const Heightfield& h, const std::string& dir) {
  std::string where;
  if (has_crs(h)) {
    const auto [lon, lat] = GeoFrame(h, "camera").lonlat_of({c.position.x, c.position.y});
    where =
        fmt::format(" (lon {:.6f}, lat {:.6f}, {:.0f} m above sea level)", lon, lat, c.position.z);
  }
  fmt::print(
      "camera: eye [{:.1f}, {:.1f}, {:.1f}] m{}, heading {:.1f}, pitch {:.1f}, fov {:.0f} "
      "degrees; instances as a scene file: {}/placed.json\n",
      c.position.x, c.position.y, c.position.z, where, c.yaw_deg, c.pitch_deg, c.fov_y_deg, dir);
}

struct SceneArgs {
  TerrainOptions terrain;
  std::string scene, models_dir = "../shared/data", size = "1280x720", json,
                     out = "out/objects_scene", cache;
  int frames = 5;
};

void add_objects_scene(CLI::App& objects, const OutputPolicy& policy) {
  auto* cmd = objects.add_subcommand(
      "scene", "a scene's objects on the terrain at full geometry: frame time, image");
  auto a = std::make_shared<SceneArgs>();
  add_terrain_options(*cmd, a->terrain);
  cmd->add_option("--scene", a->scene,
                  "scene file (JSON); default: the built-in 400-instance scene");
  cmd->add_option("--models-dir", a->models_dir, "where the default scene's models are")
      ->capture_default_str();
  cmd->add_option("--size", a->size, "image size WxH")->capture_default_str();
  cmd->add_option("--frames", a->frames, "timed frames (median reported)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--cache", a->cache,
                  "where the LOD chains and impostors are cached, or 'off' (default: "
                  "~/.cache/terrasprite/objects)");
  cmd->add_option("--json", a->json, "write the figures as JSON");
  cmd->add_option("--out", a->out,
                  "output directory (frame.png, scene.json, placed.json: the instances as placed)")
      ->capture_default_str();
  cmd->callback([a, &policy] {
    FullGeometryOptions o;
    std::tie(o.width, o.height) = parse_size(a->size, "--size");
    check_outputs(policy, a->out, {a->json});
    const Terrain terrain = load_terrain_verbose(a->terrain);
    o.scene = a->scene;
    o.models_dir = a->models_dir;
    o.frames = a->frames;
    o.cache_dir = objects_cache_dir(a->cache);
    const FullGeometryResult r = run_full_geometry(o, terrain);
    print_cache_summary(r.representation_cache);
    OutputDir out(a->out, policy);
    report::write_full_geometry(r, out, a->json, policy);
    out.commit();
    fmt::print(
        "{} instances of {} models, {} triangles at full geometry, on {} terrain triangles\n",
        r.instances, r.models.size(), r.full_triangles, r.terrain_triangles);
    fmt::print(
        "full renderer: median frame {:.1f} ms with the objects, {:.1f} ms terrain alone, at {}x{} "
        "on {}\n",
        r.median_ms, r.terrain_median_ms, r.width, r.height, r.gl_renderer);
    print_scene_camera(r.camera, terrain.heights, out.final_path().string());
  });
}

}  // namespace

void add_objects(CLI::App& app, const OutputPolicy& policy) {
  auto* objects =
      app.add_subcommand("objects", "object models: info, representations, quality tables");
  objects->require_subcommand(1);
  add_objects_info(*objects, policy);
  add_objects_table(*objects, policy);
  add_objects_scene(*objects, policy);
}

}  // namespace terrasprite::cli
