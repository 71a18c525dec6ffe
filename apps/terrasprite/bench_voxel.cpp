// SPDX-License-Identifier: MIT
// terrasprite bench voxel: options in, the voxel study (experiment/voxel.h)
// run, its report written (report/voxel_report.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <tuple>

#include "bench_commands.h"
#include "cli_common.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/voxel.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/voxel_report.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::cli {
namespace {

struct BenchVoxelOpts {
  TerrainOptions terrain;
  std::string size = "1920x1080";
  std::string path = "paper";
  int frames = 460;
  std::string threads = "1,2";
  std::string pitches = "-10,-30,-60,-90";
  int score_every = 20;
  std::string terrain_sizes = "1025,4097";
  int sweep_frames = 46;
  double ratio = 1.0;
  int supersample = 2;
  std::string json;
  std::string out;
};

// The options as the study takes them; throws InputError naming the option.
VoxelBenchOptions study_options(const BenchVoxelOpts& o) {
  VoxelBenchOptions v;
  std::tie(v.width, v.height) = parse_size(o.size, "--size");
  if (o.frames < 1 || o.frames > 100000)
    throw InputError(fmt::format("--frames {}: must be between 1 and 100000", o.frames));
  if (o.score_every < 1)
    throw InputError(fmt::format("--score-every {}: must be at least 1", o.score_every));
  v.threads.clear();
  for (double t : parse_list(o.threads, "--threads")) {
    // TBB runs at most one thread per hardware thread: a larger count would be
    // reported while fewer ran.
    const int most = int(std::max(1u, std::thread::hardware_concurrency()));
    if (t < 1 || t > most || t != std::floor(t))
      throw InputError(fmt::format(
          "--threads {}: counts must be whole, 1..{} (the hardware threads of this machine)",
          o.threads, most));
    v.threads.push_back(int(t));
  }
  v.pitches = parse_list(o.pitches, "--pitches");
  for (double p : v.pitches)
    if (p < -90 || p > 90)
      throw InputError(fmt::format("--pitches {}: angles must be within -90..90", o.pitches));
  v.terrain_sizes.clear();
  if (!o.terrain_sizes.empty() && o.terrain_sizes != "none")
    for (double s : parse_list(o.terrain_sizes, "--terrain-sizes")) {
      if (s < 2 || s > 8193 || s != std::floor(s))  // the synthetic terrain's bound
        throw InputError(
            fmt::format("--terrain-sizes {}: sizes must be whole, 2..8193", o.terrain_sizes));
      v.terrain_sizes.push_back(int(s));
    }
  v.path = o.path;
  v.frames = o.frames;
  v.score_every = o.score_every;
  v.sweep_frames = o.sweep_frames;
  v.sweep_seed = o.terrain.seed;
  v.pixel_voxel_ratio = o.ratio;
  v.supersample = o.supersample;
  return v;
}

void run(const BenchVoxelOpts& o, const OutputPolicy& policy) {
  VoxelBenchOptions v = study_options(o);
  const std::string out_dir = o.out.empty() ? std::string("out/bench_voxel") : o.out;
  check_outputs(policy, out_dir, {o.json});
  const Terrain terrain = load_terrain_verbose(o.terrain);
  OutputDir out(out_dir, policy);
  v.on_image = [&out](VoxelBenchImage kind, int i, const Image& im) {
    const char* name = kind == VoxelBenchImage::kReference ? "reference" : "multires";
    save_png(im, out.file(fmt::format("{}_{:04d}.png", name, i)));
  };
  Progress progress("bench voxel");
  v.progress = std::ref(progress);
  const VoxelBenchResult r = run_voxel_bench(terrain, v);

  const std::string error = report::write_voxel_plot(r, out.partial().string());
  if (!error.empty())
    fmt::print(stderr, "warning: {}; frame_times.dat kept without a plot\n", error);
  nlohmann::json j = report::voxel_bench_json(r);
  // JSON last: the directory is complete
  report::write_json(j, out.file("bench_voxel.json"), policy);
  out.commit();
  if (!o.json.empty()) report::write_json(j, o.json, policy);
  j.erase("per_frame");
  std::string summary =
      fmt::format("bench voxel: {} frames at {}x{}\n", r.frames, r.width, r.height);
  for (const auto& v : j["variants"])
    summary += fmt::format("  {}: median {} ms, mean SSIM {}\n", v["name"].get<std::string>(),
                           v["median_ms"].dump(), v["mean_ssim"].dump());
  print_bench_result(j, o.json, summary + fmt::format("plots and frames: {}\n", out_dir));
}

}  // namespace

void add_bench_voxel(CLI::App& bench, const OutputPolicy& policy) {
  auto* cmd = bench.add_subcommand(
      "voxel", "CPU voxel ray caster: speed per variant, thread scaling, quality vs reference");
  auto o = std::make_shared<BenchVoxelOpts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--size", o->size, "image size WxH (default 1920x1080)");
  add_path_option(*cmd, o->path);
  cmd->add_option("--frames", o->frames, "frames along the path (default 460)");
  cmd->add_option("--threads", o->threads, "thread counts to time, comma-separated (default 1,2)");
  cmd->add_option("--pitches", o->pitches, "static pitch sweep, degrees (default -10,-30,-60,-90)");
  cmd->add_option("--score-every", o->score_every,
                  "time naive and score against the reference every N-th frame (default 20)");
  cmd->add_option("--terrain-sizes", o->terrain_sizes,
                  "synthetic terrain sizes for the size sweep (default 1025,4097; 'none' to skip)");
  cmd->add_option("--sweep-frames", o->sweep_frames,
                  "frames per terrain in the size sweep (default 46)");
  cmd->add_option("--pixel-voxel-ratio", o->ratio,
                  "multires: coarsen where a voxel covers fewer pixels than this (default 1)");
  cmd->add_option("--supersample", o->supersample,
                  "reference rays per pixel side (default 2, i.e. 2x2)");
  cmd->add_option("--json", o->json,
                  "also write the JSON here (stdout then gets a short summary, not the JSON)");
  cmd->add_option(
      "--out", o->out,
      "output directory: plot, reference and multires frames, JSON (default out/bench_voxel)");
  cmd->callback([o, &policy] { run(*o, policy); });
}

}  // namespace terrasprite::cli
