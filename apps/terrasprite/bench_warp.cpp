// SPDX-License-Identifier: MIT
// terrasprite bench warp: options in, the warp study (experiment/warp.h)
// run, its report written (report/warp_report.h).
#include <fmt/format.h>

#include <tuple>

#include "bench_commands.h"
#include "cli_common.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/warp.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/warp_report.h"

namespace terrasprite::cli {
namespace {

struct BenchWarpOpts {
  TerrainOptions terrain;
  std::string renderer = "voxel";
  std::string size = "1920x1080";
  std::string path;  // empty: paper and low-fast
  int frames = 460;
  int k_max = 8;
  double margin = 0.05;
  int real_every = 4;
  std::string json;
  std::string out;
};

// The options as the study takes them; throws InputError naming the option.
WarpBenchOptions study_options(const BenchWarpOpts& o) {
  WarpBenchOptions w;
  std::tie(w.width, w.height) = parse_size(o.size, "--size");
  if (o.frames < 2 || o.frames > 100000)
    throw InputError(fmt::format("--frames {}: must be between 2 and 100000", o.frames));
  if (o.k_max < 1 || o.k_max > 64)
    throw InputError(fmt::format("--k-max {}: must be within 1..64", o.k_max));
  if (o.real_every < 1 || o.real_every > 64)
    throw InputError(fmt::format("--real-every {}: must be within 1..64", o.real_every));
  if (!(o.margin >= 0 && o.margin <= 1))
    throw InputError(fmt::format("--margin {}: must be within 0..1", o.margin));
  if (o.renderer != "voxel" && o.renderer != "full")
    throw InputError(fmt::format("--renderer {}: expected voxel or full", o.renderer));
  w.renderer = parse_render_mode(o.renderer, "--renderer");
  if (!o.path.empty()) w.paths = {o.path};
  w.frames = o.frames;
  w.k_max = o.k_max;
  w.margin = o.margin;
  w.real_every = o.real_every;
  return w;
}

void run(const BenchWarpOpts& o, const OutputPolicy& policy) {
  WarpBenchOptions w = study_options(o);
  const std::string out_dir = o.out.empty() ? std::string("out/bench_warp") : o.out;
  check_outputs(policy, out_dir, {o.json});
  const Terrain terrain = load_terrain_verbose(o.terrain);
  Progress progress("bench warp");
  w.progress = std::ref(progress);
  const WarpBenchResult r = run_warp_bench(terrain, w);

  OutputDir out(out_dir, policy);
  const std::string error = report::write_warp_plot(r, out.partial().string());
  if (!error.empty())
    fmt::print(stderr, "warning: {}; quality_vs_k.dat kept without a plot\n", error);
  const nlohmann::json j = report::warp_bench_json(r);
  // JSON last: the directory is complete
  report::write_json(j, out.file("bench_warp.json"), policy);
  out.commit();
  if (!o.json.empty()) report::write_json(j, o.json, policy);
  std::string summary = "bench warp: per method and path, median warp / real frame ms\n";
  for (const auto& m : j["methods"])
    summary += fmt::format("  {} on {}: {} / {} ms\n", m["name"].get<std::string>(),
                           m["path"].get<std::string>(), m["warp_ms_median"].dump(),
                           m["real_ms_median"].dump());
  print_bench_result(j, o.json, summary + fmt::format("plot: {}\n", out_dir));
}

}  // namespace

void add_bench_warp(CLI::App& bench, const OutputPolicy& policy) {
  auto* cmd = bench.add_subcommand("warp", "post-render warp quality and cost against real frames");
  auto o = std::make_shared<BenchWarpOpts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--renderer", o->renderer, "renderer of the real frames: voxel (default) or full")
      ->check(CLI::IsMember({"voxel", "full"}));
  cmd->add_option("--size", o->size, "output image size WxH (default 1920x1080)");
  add_path_option(*cmd, o->path, "both built-in paths, one after the other");
  cmd->add_option("--frames", o->frames, "frames along each path (default 460)");
  cmd->add_option("--k-max", o->k_max, "warp up to this many frames past a real one (default 8)");
  cmd->add_option("--margin", o->margin,
                  "real frames drawn this fraction wider on each side (default 0.05)");
  cmd->add_option(
      "--real-every", o->real_every,
      "K for the flythrough cost figure: one real frame per K output frames (default 4)");
  cmd->add_option("--json", o->json,
                  "also write the JSON here (stdout then gets a short summary, not the JSON)");
  cmd->add_option("--out", o->out, "output directory: plot, JSON (default out/bench_warp)");
  cmd->callback([o, &policy] { run(*o, policy); });
}

}  // namespace terrasprite::cli
