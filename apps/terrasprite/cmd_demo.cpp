// SPDX-License-Identifier: MIT
// terrasprite demo: the main job on the embedded default (synthetic terrain,
// paper path), frames + stats into out/demo/.
#include <fmt/format.h>

#include "cli_common.h"
#include "commands.h"
#include "render_modes.h"
#include "terrasprite/camera_path.h"
#include "terrasprite/flythrough.h"
#include "terrasprite/output_dir.h"

namespace terrasprite::cli {

void add_demo(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "demo", "fly the paper path over the default terrain, writing frames and stats");
  struct Opts {
    TerrainOptions terrain;
    std::string out = "out/demo";
    int frames = 460;
    std::string size = "512x512";
  };
  auto o = std::make_shared<Opts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--out", o->out, "output directory (default out/demo)");
  cmd->add_option("--frames", o->frames, "frames along the paper path (default 460)");
  cmd->add_option("--size", o->size, "image size WxH (default 512x512)");
  cmd->callback([o] {
    auto [w, h] = parse_size(o->size, "--size");
    Terrain terrain = load_terrain_verbose(o->terrain);
    std::vector<Camera> path = make_path("paper", terrain.heights, o->frames, double(w) / h);
    RenderStack stack = make_render_stack("full", terrain, w, h, 0);
    OutputDir out(o->out);
    Progress progress("demo");
    auto stats = fly(
        *stack.renderer, path,
        [&](int i, const Frame& f) {
          save_png(f.color, out.file(fmt::format("frames/frame_{:04d}.png", i)));
        },
        std::ref(progress));
    nlohmann::json frames = nlohmann::json::array();
    std::vector<double> ms;
    for (const auto& s : stats) {
      frames.push_back(
          {{"frame", s.frame}, {"class", s.cls}, {"ms", s.ms}, {"triangles", s.triangles}});
      ms.push_back(s.ms);
    }
    nlohmann::json j = {{"gl_renderer", stack.device},
                        {"mode", "full"},
                        {"size", {w, h}},
                        {"terrain", terrain_json(terrain)},
                        {"path", "paper"},
                        {"median_ms", median(ms)},
                        {"frames", frames}};
    write_json(j, out.file("stats.json"));
    out.commit();
    fmt::print("demo: {} paper-path frames of {} at {}x{}, median {:.2f} ms/frame on {} -> {}\n",
               stats.size(), terrain.heights.name, w, h, median(ms), stack.device,
               out.final_path().string());
  });
}

}  // namespace terrasprite::cli
