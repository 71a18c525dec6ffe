// SPDX-License-Identifier: MIT
// terrasprite objects scene: a scene's objects on the terrain at full
// geometry, all in view -- the frame time a budget has to beat.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "cli_common.h"
#include "objects_table.h"
#include "scene_objects.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/objects/object_set.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/raster/scene.h"

namespace terrasprite::cli {
namespace {

// From the south, 35 degrees down, far enough that every instance is in view.
Camera overview_camera(const ObjectSet& set, const Heightfield& h, double aspect) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (std::size_t m = 0; m < set.model_count(); ++m)
    for (const ObjectInstance& i : set.instances(m)) {
      lo = glm::min(lo, i.position);
      hi = glm::max(hi, i.position);
    }
  const glm::dvec3 c = 0.5 * (lo + hi);
  const double r = 0.5 * glm::length(hi - lo) + 10.0;
  const double fov = 50.0, dist = r / std::sin(glm::radians(std::min(fov, fov * aspect) / 2));
  const double e = glm::radians(35.0);
  Camera cam = Camera::look_at(c + dist * glm::dvec3(0, -std::cos(e), std::sin(e)), c, fov, aspect);
  fit_clip_planes(cam, h);
  return cam;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

void add_objects_scene(CLI::App& objects) {
  auto* cmd = objects.add_subcommand(
      "scene", "a scene's objects on the terrain at full geometry: frame time, image");
  struct Opts {
    TerrainOptions terrain;
    std::string scene, models_dir = "../shared/data", size = "1280x720", json,
                       out = "out/objects_scene", cache;
    int frames = 5;
  };
  auto o = std::make_shared<Opts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--scene", o->scene,
                  "scene file (JSON); default: the built-in 400-instance scene");
  cmd->add_option("--models-dir", o->models_dir, "where the default scene's models are")
      ->capture_default_str();
  cmd->add_option("--size", o->size, "image size WxH")->capture_default_str();
  cmd->add_option("--frames", o->frames, "timed frames (median reported)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--cache", o->cache,
                  "where the LOD chains and impostors are cached, or 'off' (default: "
                  "~/.cache/terrasprite/objects)");
  cmd->add_option("--json", o->json, "write the figures as JSON");
  cmd->add_option("--out", o->out, "output directory (frame.png, scene.json)")
      ->capture_default_str();
  cmd->callback([o] {
    auto [w, h] = parse_size(o->size, "--size");
    check_outputs(o->out, {o->json});
    const Terrain terrain = load_terrain_verbose(o->terrain);
    const ObjectScene scene = o->scene.empty()
                                  ? default_object_scene(o->models_dir, terrain.heights)
                                  : load_object_scene(o->scene, terrain.heights);
    OutputDir out(o->out, output_policy());
    GlContext gl;
    Scene ground(terrain);
    const auto load_start = std::chrono::steady_clock::now();
    ObjectSet objects(scene, LodOptions{}, objects_cache_dir(o->cache));
    const double load_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start)
            .count();
    print_cache_summary(objects);
    const Camera cam = overview_camera(objects, terrain.heights, double(w) / h);
    // The full-resolution renderer with and without the scene's objects,
    // interleaved frame by frame; frame 0 warms up (shaders, uploads).
    MeshRenderer full(ground, w, h, 0);
    std::vector<double> total_ms, terrain_ms;
    long long triangles = 0, terrain_triangles = 0;
    for (int f = 0; f <= o->frames; ++f) {
      ground.set_objects(&objects);
      const Frame a = full.draw(cam);
      if (f == o->frames) {
        Frame img = a;
        full.read_back(img, ReadBack::kColor);
        save_png(img.color, out.file("frame.png"));
      }
      ground.set_objects(nullptr);
      const Frame b = full.draw(cam);
      if (f == 0) continue;
      total_ms.push_back(a.ms);
      terrain_ms.push_back(b.ms);
      triangles = a.triangles;
      terrain_triangles = b.triangles;
    }
    nlohmann::json models = nlohmann::json::array();
    for (std::size_t m = 0; m < objects.model_count(); ++m)
      models.push_back({{"name", objects.scene_model(m).name},
                        {"file", objects.scene_model(m).file},
                        {"triangles", objects.model(m).model().triangles()},
                        {"instances", objects.instances(m).size()},
                        {"lod_levels", objects.model(m).chain().size()}});
    nlohmann::json j = {{"gl_renderer", gl.renderer()},
                        {"size", {w, h}},
                        {"instances", objects.instance_count()},
                        {"load_ms", load_ms},
                        {"representation_cache", cache_stats_json(objects.cache_stats())},
                        {"full_triangles", objects.full_triangles()},
                        {"terrain_triangles", terrain_triangles},
                        {"frame_triangles", triangles},
                        {"frames", o->frames},
                        {"median_ms", median(total_ms)},
                        {"terrain_median_ms", median(terrain_ms)},
                        {"models", models}};
    write_json(j, out.file("scene.json"));
    if (!o->json.empty()) write_json(j, o->json);
    out.commit();
    fmt::print(
        "{} instances of {} models, {} triangles at full geometry, on {} terrain triangles\n",
        objects.instance_count(), objects.model_count(), objects.full_triangles(),
        terrain_triangles);
    fmt::print(
        "full renderer: median frame {:.1f} ms with the objects, {:.1f} ms terrain alone, at {}x{} "
        "on {}\n",
        median(total_ms), median(terrain_ms), w, h, gl.renderer());
  });
}

}  // namespace terrasprite::cli
