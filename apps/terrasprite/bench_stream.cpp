// SPDX-License-Identifier: MIT
// terrasprite bench stream: options in, the streaming study
// (experiment/stream.h) run, its report written (report/stream_report.h).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <tuple>

#include "bench_commands.h"
#include "cli_common.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/stream.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/stream_report.h"

namespace terrasprite::cli {
namespace {

struct BenchStreamOpts {
  std::string tiles;
  std::string cog, texture;
  int cache_mb = 256;
  int io_threads = 2;
  std::string size = "1920x1080";
  std::string path = "low-fast";
  int frames = 300;
  int threads = 0;
  std::string in_memory = "auto";
  int first_view_ms = 600;  // longest wait for the first view's tiles before frame 0
  bool child = false;  // hidden: be the in-memory peer (frame numbers on fd 3, answers on fd 4)
  std::string json;
  std::string out;
};

// This program again, as the in-memory peer of the run `o` asks for.
std::vector<std::string> peer_command(const BenchStreamOpts& o) {
  std::vector<std::string> args = {"/proc/self/exe",
                                   "bench",
                                   "stream",
                                   o.cog.empty() ? "--tiles" : "--cog",
                                   o.cog.empty() ? o.tiles : o.cog,
                                   "--size",
                                   o.size,
                                   "--path",
                                   o.path,
                                   "--frames",
                                   std::to_string(o.frames),
                                   "--threads",
                                   std::to_string(o.threads),
                                   "--first-view-ms",
                                   std::to_string(o.first_view_ms),
                                   "--in-memory-child"};
  if (!o.texture.empty()) args.insert(args.end(), {"--texture", o.texture});
  return args;
}

// The options as the study takes them; throws InputError naming the option.
StreamBenchOptions study_options(const BenchStreamOpts& o) {
  StreamBenchOptions s;
  std::tie(s.width, s.height) = parse_size(o.size, "--size");
  if (o.frames < 1 || o.frames > 100000)
    throw InputError(fmt::format("--frames {}: must be between 1 and 100000", o.frames));
  if (o.first_view_ms < 0 || o.first_view_ms > 60000)
    throw InputError(
        fmt::format("--first-view-ms {}: must be between 0 and 60000", o.first_view_ms));
  if (o.cache_mb < 1 || o.cache_mb > 1 << 20)
    throw InputError(fmt::format("--cache-mb {}: must be between 1 and 1048576", o.cache_mb));
  s.tiles = o.tiles;
  s.cog = o.cog;
  s.texture = o.texture;
  s.cache_mb = o.cache_mb;
  s.io_threads = o.io_threads;
  s.path = o.path;
  s.frames = o.frames;
  s.threads = o.threads;
  s.first_view_ms = o.first_view_ms;
  s.in_memory = o.in_memory == "yes"  ? InMemoryRun::kYes
                : o.in_memory == "no" ? InMemoryRun::kNo
                                      : InMemoryRun::kAuto;
  s.peer_command = peer_command(o);
  return s;
}

void run(const BenchStreamOpts& o, const OutputPolicy& policy) {
  StreamBenchOptions s = study_options(o);
  if (o.child) return run_stream_peer(s);
  const std::string out_dir = o.out.empty() ? std::string("out/bench_stream") : o.out;
  check_outputs(policy, out_dir, {o.json});
  Progress progress("bench stream");
  s.progress = std::ref(progress);
  const StreamBenchResult r = run_stream_bench(s);

  OutputDir out(out_dir, policy);
  const std::string error = report::write_stream_plot(r, out.partial().string());
  if (!error.empty())
    fmt::print(stderr, "warning: {}; stream_frames.dat kept without a plot\n", error);
  const std::vector<std::string> images = report::write_stream_snapshots(r, out.partial().string());
  const nlohmann::json summary = report::stream_bench_json(r);
  nlohmann::json full = summary;
  full["per_frame"] = report::stream_per_frame_json(r);
  // JSON last: the directory is complete
  report::write_json(full, out.file("bench_stream.json"), policy);
  out.commit();
  if (!o.json.empty()) report::write_json(full, o.json, policy);
  print_bench_result(summary, o.json,
                     report::stream_summary_text(r) +
                         fmt::format("images: {} in {}\n", fmt::join(images, ", "), out_dir));
}

// --dem is not a streamed terrain: refused with the command that makes one.
void add_dem_hint(CLI::App& cmd) {
  cmd.add_option_function<std::string>(
         "--dem",
         [](const std::string& dem) {
           throw InputError(fmt::format(
               "--dem {0}: bench stream reads a tiled terrain; run `terrasprite tile --dem {0} "
               "--out DIR` first, then `bench stream --tiles DIR`",
               dem));
         },
         "")
      ->group("");  // hidden: only there to give the hint
}

}  // namespace

void add_bench_stream(CLI::App& bench, const OutputPolicy& policy) {
  auto* cmd = bench.add_subcommand(
      "stream",
      "streamed terrain: frame times, stalls and degraded reads vs the terrain in memory");
  auto o = std::make_shared<BenchStreamOpts>();
  cmd->add_option("--tiles", o->tiles, "tiled terrain directory (terrasprite tile --out DIR)");
  cmd->add_option("--cog", o->cog,
                  "an existing COG or tiled GeoTIFF with overviews, one band of heights (instead "
                  "of --tiles)");
  cmd->add_option("--texture", o->texture, "with --cog: an RGB raster of the same size (colour)");
  cmd->add_option("--cache-mb", o->cache_mb, "tile cache budget, MB (default 256)");
  cmd->add_option("--io-threads", o->io_threads, "loader threads (default 2)");
  cmd->add_option("--size", o->size, "image size WxH (default 1920x1080)");
  add_path_option(*cmd, o->path);
  cmd->add_option("--frames", o->frames, "frames along the path (default 300)");
  cmd->add_option("--threads", o->threads, "ray-caster threads (default 0: all)");
  cmd->add_option("--first-view-ms", o->first_view_ms,
                  "before frame 0, wait at most this long for the tiles its view reads (default "
                  "600; 0: draw frame 0 from whatever is resident)");
  cmd->add_option("--in-memory", o->in_memory,
                  "also fly the terrain wholly in memory, in another process: auto (default: when "
                  "it fits in half the free memory), yes, no")
      ->check(CLI::IsMember({"auto", "yes", "no"}));
  cmd->add_flag("--in-memory-child", o->child)->group("");  // internal
  add_dem_hint(*cmd);
  cmd->add_option("--json", o->json,
                  "also write the JSON here (stdout then gets a short summary, not the JSON)");
  cmd->add_option("--out", o->out,
                  "output directory: plot, first/middle/last frames (frame_NNNN.png), JSON "
                  "(default out/bench_stream)");
  cmd->callback([o, &policy] { run(*o, policy); });
}

}  // namespace terrasprite::cli
