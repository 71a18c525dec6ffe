// SPDX-License-Identifier: MIT
// terrasprite demo: the main job on the embedded default (synthetic terrain,
// paper path) with LOD-sprite: frames, stats and the report into out/demo/.
#include <fmt/format.h>

#include "cli_common.h"
#include "commands.h"
#include "lodsprite_report.h"
#include "lodsprite_run.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/output/video_writer.h"

namespace terrasprite::cli {

void add_demo(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "demo", "fly the paper path over the default terrain with LOD-sprite: frames, stats, report");
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
    check_outputs(o->out, {});
    Terrain terrain = load_terrain_verbose(o->terrain);
    OutputDir out(o->out, output_policy());
    // The bench's run, lighter sweeps: frames, stats and the report in minutes.
    LodspriteConfig c;
    c.frames = o->frames;
    c.width = w;
    c.height = h;
    c.thresholds = {0.5, 1, 2, 4};
    c.frame_counts = {115, 230, 460, 920};
    c.lod_sweep = {8, 16, 32};
    c.sweep_score_every = 4;
    c.flip = false;  // FLIP is the slowest score; the bench has it
    VideoWriter video(out.file("flythrough.mp4"), w, h);  // the flight at 30 fps
    c.video = "flythrough.mp4";
    c.on_sprite_frame = [&](int i, const Frame& f) {
      save_png(f.color, out.file(fmt::format("frames/frame_{:04d}.png", i)));
      video.push(f.color);
    };
    const LodspriteResult r = run_lodsprite(c, terrain, out, "demo");
    video.finish();
    write_lodsprite_report(r, out);
    const nlohmann::json report = to_json(r);
    nlohmann::json frames = nlohmann::json::array();
    for (const LodspriteFrame& p : r.per_frame)
      frames.push_back({{"frame", p.frame},
                        {"class", p.key ? "key" : "sprite"},
                        {"ms", p.ms},
                        {"error_px", p.error_px},
                        {"error_px_exact", p.error_px_exact},
                        {"psnr", p.sprite.psnr},
                        {"ssim", p.sprite.ssim}});
    nlohmann::json j = {{"gl_renderer", r.gl_renderer},
                        {"mode", "sprite"},
                        {"size", {w, h}},
                        {"terrain", report["terrain"]},
                        {"path", "paper"},
                        {"median_ms", r.sprite.median_ms},
                        {"speedup", r.speedup},
                        {"keyframes", r.sprite.keyframes},
                        {"full", report["full"]},
                        {"lod", report["lod"]},
                        {"sprite", report["sprite"]},
                        {"bound", report["bound"]},
                        {"frames", frames}};
    write_json(report, out.file("lodsprite.json"));
    write_json(j, out.file("stats.json"));  // JSON last: the directory is complete
    out.commit();
    fmt::print(
        "demo: {} paper-path frames of {} at {}x{} with LOD-sprite: {} keyframes, speed-up {:.2f}x "
        "over full resolution (bound {:.2f}x), SSIM {:.4f} vs plain LOD {:.4f}, on {} -> "
        "{}/index.html\n",
        r.frames, terrain.heights.name, w, h, r.sprite.keyframes, r.speedup, r.bound.speedup_bound,
        r.sprite.mean_ssim, r.lod.mean_ssim, r.gl_renderer, out.final_path().string());
  });
}

}  // namespace terrasprite::cli
