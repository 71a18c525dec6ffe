// SPDX-License-Identifier: MIT
// terrasprite demo: the main job on the embedded default (synthetic terrain,
// paper path) with LOD-sprite: frames, video, stats and the report into out/demo/.
#include <fmt/format.h>

#include "cli_common.h"
#include "commands.h"
#include "terrasprite/experiment/lodsprite/lodsprite.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/output/video_writer.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/lodsprite_json.h"
#include "terrasprite/report/lodsprite_report.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::cli {
namespace {

struct DemoOptions {
  TerrainOptions terrain;
  std::string out = "out/demo";
  int frames = 460;
  std::string size = "512x512";
  bool sweeps = false;
};

// The bench's run with lighter sweeps, and those only when asked for: the
// main run alone gives the flight and Figs. 8-9 and 13-14 (the sweeps' share:
// docs/results/2026-12-07-demo-time.md).
lodsprite::LodspriteOptions run_options(const DemoOptions& o, int w, int h) {
  lodsprite::LodspriteOptions c;
  c.frames = o.frames;
  c.width = w;
  c.height = h;
  c.thresholds.clear();
  c.frame_counts.clear();
  c.lod_sweep.clear();
  if (o.sweeps) {
    c.thresholds = {0.5, 1, 2, 4};
    c.frame_counts = {115, 230, 460, 920};
    c.lod_sweep = {8, 16, 32};
  }
  c.sweep_score_every = 4;
  c.flip = false;  // FLIP is the slowest score; the bench has it
  c.video = "flythrough.mp4";
  c.progress = stage_progress("demo");
  return c;
}

// Three lines: what ran, what it found, where the report is.
void print_summary(const lodsprite::LodspriteResult& r, const Terrain& terrain,
                   const OutputDir& out) {
  fmt::print("demo: {} paper-path frames of {} at {}x{} with LOD-sprite on {}\n", r.frames,
             terrain.heights.name, r.width, r.height, r.gl_renderer);
  fmt::print(
      "found: {} keyframes, speed-up {:.2f}x over full resolution (bound {:.2f}x), SSIM {:.4f} "
      "vs plain LOD {:.4f}\n",
      r.sprite.keyframes, r.speedup, r.bound.speedup_bound, r.sprite.mean_ssim, r.lod.mean_ssim);
  fmt::print("report: {}/index.html\n", out.final_path().string());
}

}  // namespace

void add_demo(CLI::App& app, const OutputPolicy& policy) {
  auto* cmd = app.add_subcommand(
      "demo", "fly the paper path over the default terrain with LOD-sprite: frames, stats, report");
  auto o = std::make_shared<DemoOptions>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--out", o->out, "output directory (default out/demo)");
  cmd->add_option("--frames", o->frames, "frames along the paper path (default 460)");
  cmd->add_option("--size", o->size, "image size WxH (default 512x512)");
  cmd->add_flag("--sweeps", o->sweeps,
                "also run the paper's sweeps (its Figs. 10-12: thresholds 0.5,1,2,4, frame counts "
                "115..920, coarse meshes 8,16,32): a few minutes more; `bench lodsprite` has the "
                "full ones");
  cmd->callback([o, &policy] {
    auto [w, h] = parse_size(o->size, "--size");
    check_outputs(policy, o->out, {});
    Terrain terrain = load_terrain_verbose(o->terrain);
    OutputDir out(o->out, policy);
    lodsprite::LodspriteOptions c = run_options(*o, w, h);
    VideoWriter video(out.file(c.video), w, h);  // the flight at 30 fps
    // Called between frames, outside the timed spans: nothing of ours encodes
    // while a frame is timed (llvmpipe uses every core).
    c.on_sprite_frame = [&](int i, const Frame& f) {
      save_png(f.color, out.file(fmt::format("frames/frame_{:04d}.png", i)));
      video.push(f.color);
    };
    const lodsprite::LodspriteResult r = lodsprite::run_lodsprite(c, terrain);
    video.finish();
    report::write_lodsprite_report(r, out);
    report::write_json(report::lodsprite_json(r), out.file("lodsprite.json"), policy);
    // last: the directory is complete
    report::write_json(report::demo_stats_json(r), out.file("stats.json"), policy);
    out.commit();
    print_summary(r, terrain, out);
  });
}

}  // namespace terrasprite::cli
