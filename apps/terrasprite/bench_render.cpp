// SPDX-License-Identifier: MIT
// terrasprite bench render: full resolution against plain LOD on the same path,
// interleaved frame by frame so machine noise hits both alike.
#include <fmt/format.h>

#include "bench_commands.h"
#include "cli_common.h"
#include "objects_options.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/report/json_writer.h"

namespace terrasprite::cli {

void add_bench_render(CLI::App& bench, const OutputPolicy& policy) {
  auto* cmd = bench.add_subcommand(
      "render", "full-resolution vs LOD frame times on one path (JSON on stdout)");
  struct Opts {
    TerrainOptions terrain;
    int lod_quads = 16;
    std::string path = "paper";
    int frames = 460;
    std::string size = "512x512";
    std::string json;
    ObjectsOptions objects;
  };
  auto o = std::make_shared<Opts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--lod-quads", o->lod_quads, "coarse grid quads per side (default 16)");
  add_path_option(*cmd, o->path);
  cmd->add_option("--frames", o->frames, "frames (default 460)")->check(CLI::Range(1, 1000000));
  cmd->add_option("--size", o->size, "image size WxH (default 512x512)");
  cmd->add_option("--json", o->json,
                  "also write the JSON here (stdout then gets a short summary, not the JSON)");
  add_objects_options(*cmd, o->objects);
  cmd->callback([o, &policy] {
    auto [w, h] = parse_size(o->size, "--size");
    check_outputs(policy, "", {o->json});
    Terrain terrain = load_terrain_verbose(o->terrain);
    check_lod_quads(o->lod_quads, terrain.heights);
    std::vector<Camera> path = make_path(o->path, terrain.heights, o->frames, double(w) / h);
    GlContext gl;
    Scene scene(terrain);
    const std::unique_ptr<GlSceneObjects> objects =
        attach_objects(o->objects, terrain, &scene, "full");
    MeshRenderer full(scene, w, h, 0), lod(scene, w, h, o->lod_quads);
    Experiment experiment;
    experiment.add({.renderer = &full, .name = "full"});
    experiment.add({.renderer = &lod, .name = "lod"});
    PathSource cameras(std::move(path));
    Progress progress("bench render");
    const ExperimentResult r = experiment.run(cameras, {.progress = std::ref(progress)});
    auto entry = [](const RendererRun& run) {
      const Summary ms = run.ms(), gpu = run.gpu_ms();
      return nlohmann::json{{"median_ms", ms.median},
                            {"p99_ms", ms.p99},
                            {"total_ms", ms.total},
                            {"median_gpu_ms", gpu.count ? nlohmann::json(gpu.median) : nullptr},
                            {"triangles", run.frames.back().triangles}};
    };
    const RendererRun &f = r.run("full"), &l = r.run("lod");
    nlohmann::json lod_json = entry(l);
    lod_json["lod_quads"] = o->lod_quads;
    nlohmann::json j = {{"gl_renderer", gl.renderer()},
                        {"terrain", terrain_json(terrain)},
                        {"size", {w, h}},
                        {"frames", r.frames},
                        {"path", o->path},
                        {"objects", objects ? objects->instance_count() : 0},
                        {"full", entry(f)},
                        {"lod", lod_json},
                        {"full_over_lod_median", f.ms().median / std::max(l.ms().median, 1e-9)}};
    if (!o->json.empty()) report::write_json(j, o->json, policy);
    print_bench_result(
        j, o->json,
        fmt::format("bench render: {} frames at {}x{}: full resolution median {:.2f} ms, LOD "
                    "({} quads) median {:.2f} ms, {:.2f}x\n",
                    r.frames, w, h, f.ms().median, o->lod_quads, l.ms().median,
                    f.ms().median / std::max(l.ms().median, 1e-9)));
  });
}

}  // namespace terrasprite::cli
