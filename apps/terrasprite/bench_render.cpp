// SPDX-License-Identifier: MIT
// terrasprite bench render: full resolution against plain LOD on the same path,
// interleaved frame by frame so machine noise hits both alike.
#include <fmt/format.h>

#include "bench_commands.h"
#include "cli_common.h"
#include "terrasprite/camera_path.h"
#include "terrasprite/flythrough.h"
#include "terrasprite/gl_context.h"
#include "terrasprite/mesh_renderer.h"

namespace terrasprite::cli {

void add_bench_render(CLI::App& bench) {
  auto* cmd = bench.add_subcommand(
      "render", "full-resolution vs LOD frame times on one path (JSON on stdout)");
  struct Opts {
    TerrainOptions terrain;
    int lod_quads = 16;
    std::string path = "paper";
    int frames = 460;
    std::string size = "512x512";
    std::string json;
  };
  auto o = std::make_shared<Opts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--lod-quads", o->lod_quads, "coarse grid quads per side (default 16)");
  cmd->add_option("--path", o->path, "'paper' or a JSON path file");
  cmd->add_option("--frames", o->frames, "frames (default 460)");
  cmd->add_option("--size", o->size, "image size WxH (default 512x512)");
  cmd->add_option("--json", o->json, "also write the JSON here");
  cmd->callback([o] {
    auto [w, h] = parse_size(o->size, "--size");
    check_outputs("", {o->json});
    Terrain terrain = load_terrain_verbose(o->terrain);
    check_lod_quads(o->lod_quads, terrain.heights);
    std::vector<Camera> path = make_path(o->path, terrain.heights, o->frames, double(w) / h);
    GlContext gl;
    GlTerrain scene(terrain);
    RasterOptions ro;
    ro.read_depth = false;
    MeshRenderer full(scene, w, h, 0, ro), lod(scene, w, h, o->lod_quads, ro);
    full.render(path[0]);  // warm-up: shader compilation and first-use costs
    lod.render(path[0]);
    std::vector<double> f_ms, l_ms, f_gpu, l_gpu;
    long long f_tri = 0, l_tri = 0;
    Progress progress("bench render");
    for (std::size_t i = 0; i < path.size(); ++i) {
      Frame a = full.render(path[i]);
      Frame b = lod.render(path[i]);
      f_ms.push_back(a.ms);
      l_ms.push_back(b.ms);
      f_gpu.push_back(a.gpu_ms);
      l_gpu.push_back(b.gpu_ms);
      f_tri = a.triangles;
      l_tri = b.triangles;
      progress(int(i) + 1, int(path.size()));
    }
    auto total = [](const std::vector<double>& v) {
      double s = 0;
      for (double x : v) s += x;
      return s;
    };
    nlohmann::json j = {{"gl_renderer", gl.renderer()},
                        {"terrain", terrain_json(terrain)},
                        {"size", {w, h}},
                        {"frames", int(path.size())},
                        {"path", o->path},
                        {"full",
                         {{"median_ms", median(f_ms)},
                          {"total_ms", total(f_ms)},
                          {"median_gpu_ms", median(f_gpu)},
                          {"triangles", f_tri}}},
                        {"lod",
                         {{"lod_quads", o->lod_quads},
                          {"median_ms", median(l_ms)},
                          {"total_ms", total(l_ms)},
                          {"median_gpu_ms", median(l_gpu)},
                          {"triangles", l_tri}}},
                        {"full_over_lod_median", median(f_ms) / std::max(median(l_ms), 1e-9)}};
    if (!o->json.empty()) write_json(j, o->json);
    fmt::print("{}\n", j.dump(2));
  });
}

}  // namespace terrasprite::cli
