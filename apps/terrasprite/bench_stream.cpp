// SPDX-License-Identifier: MIT
// terrasprite bench stream: a flythrough over a tiled terrain read through the
// streaming tile cache (load on demand, prefetch, never wait), then the same
// frames with the whole terrain in memory in a separate process (so its
// memory does not count against the streamed run), compared frame by frame:
// time, stalls, degraded reads and identical images once tiles are resident.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <future>
#include <memory>
#include <optional>

#include "bench_commands.h"
#include "bench_stream_peer.h"
#include "cli_common.h"
#include "terrasprite/report/plot.h"
#include "process_memory.h"
#include "stream/cog_source.h"
#include "stream/tile_file.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/stream/streaming_tiles.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite::cli {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The path is planned over a coarse level of the tiled terrain (at most 1025
// samples a side), read once: the full-resolution grid never loads.
Heightfield path_proxy(const TileSetInfo& set) {
  int L = 0;
  while (L < set.grid.coarsest_level && std::max(set.level_w(L), set.level_h(L)) > 1025) ++L;
  Heightfield h;
  std::string error;
  if (!TileFile(set).read_level_heights(L, h.heights, error))
    throw InputError(fmt::format("{}: {}", set.dir, error));
  h.width = set.level_w(L);
  h.height = set.level_h(L);
  h.spacing_x = set.grid.spacing_x * (set.grid.width - 1) / double(h.width - 1);
  h.spacing_y = set.grid.spacing_y * (set.grid.height - 1) / double(h.height - 1);
  h.name = set.dir;
  return h;
}

/// The ray caster over the streaming cache: each draw first lets the cache
/// update (install finished reads, queue the footprint; never waits), and
/// that update counts in the frame's time.
class StreamedVoxel final : public Renderer {
 public:
  StreamedVoxel(StreamingTiles& tiles, int w, int h, VoxelOptions vo)
      : tiles_(tiles), r_(tiles, w, h, vo) {}
  Frame draw(const Camera& c) override {
    const auto t0 = Clock::now();
    last_ = tiles_.update(c);
    update_ms_ = ms_since(t0);
    Frame f = r_.draw(c);
    tiles_.collect_reads(last_);
    f.ms += update_ms_;
    return f;
  }
  /// Before frame 0: a draw at `c` that is not shown (it warms the renderer
  /// and marks the tiles the view misses), then a wait of at most until
  /// `deadline` for those tiles. Counts in time to first frame.
  StreamingTiles::FirstView prime(const Camera& c, Clock::time_point deadline) {
    r_.draw(c);
    return tiles_.wait_for_first_view(c, deadline);
  }
  void read_back(Frame& f, ReadBack what) override { r_.read_back(f, what); }
  std::string name() const override { return "stream"; }
  const StreamFrameStats& last() const { return last_; }
  double update_ms() const { return update_ms_; }

 private:
  StreamingTiles& tiles_;
  VoxelRenderer r_;
  StreamFrameStats last_;
  double update_ms_ = 0;
};

struct PerFrame {
  double ms = 0, update_ms = 0;
  StreamFrameStats st;
  std::uint64_t hash = 0;
};

struct StreamRun {
  std::vector<PerFrame> frames;
  double first_frame_ms = 0, wall_ms = 0, peak_rss_mb = 0;
  int faults_injected = 0, faults_survived = 0;
  std::size_t pinned_bytes = 0;
  double open_ms = 0, path_ms = 0, pinned_ms = 0;  // before the first frame
  double first_view_ms = 0;                        // the unshown draw and the wait after it
  StreamingTiles::FirstView first_view;
  // The in-memory run's frames, one per streamed frame while its process lives.
  std::vector<double> in_memory_ms;
  std::vector<std::uint64_t> in_memory_hash;
  double in_memory_peak_rss_mb = 0;
  double peer_wait_ms = 0;  ///< waiting for the peer's frames: not the streamed run's time
};

StreamOptions stream_options(const BenchStreamOpts& o, int h) {
  StreamOptions so;
  so.cache_bytes = std::size_t(o.cache_mb) << 20;
  so.io_threads = o.io_threads;
  so.image_height = h;
  return so;
}

// `tiles` is open with its coarse levels pinned; `t_start` is when the frames begin.
StreamRun run_streamed(const BenchStreamOpts& o, StreamingTiles& tiles, Clock::time_point t_start,
                       int w, int h, const std::vector<Camera>& path, InMemoryPeer* peer) {
  VoxelOptions vo;
  vo.threads = o.threads;
  StreamedVoxel renderer(tiles, w, h, vo);
  StreamRun run;
  run.pinned_bytes = tiles.pinned_bytes();
  Experiment ex;
  ex.add({.renderer = &renderer,
          .name = "stream",
          .warmup_draws = 0,  // the first frame is part of the figures (time to first frame)
          .annotate = [&](const Frame& f, FrameResult& r) {
            if (run.frames.empty()) run.first_frame_ms = ms_since(t_start);
            const StreamFrameStats& st = renderer.last();
            run.frames.push_back({f.ms, renderer.update_ms(), st, image_hash(f.color)});
            r.counters["degraded_samples"] = double(st.degraded_samples);
            r.counters["tiles_loaded"] = st.loaded;
            // After the timed span: the same frame in memory, in the other process.
            ChildReply m;
            const auto t_peer = Clock::now();
            if (peer && peer->frame(int(run.frames.size()) - 1, m)) {
              run.in_memory_ms.push_back(m.ms);
              run.in_memory_hash.push_back(m.hash);
            }
            run.peer_wait_ms += ms_since(t_peer);
          }});
  ExperimentOptions eo;
  eo.warmup_draws = 0;
  Progress progress("bench stream");
  eo.progress = std::ref(progress);
  PathSource cameras(path);
  const auto t_run = Clock::now();
  if (o.first_view_ms > 0 && !path.empty()) {
    run.first_view =
        renderer.prime(path.front(), t_run + std::chrono::milliseconds(o.first_view_ms));
    run.first_view_ms = ms_since(t_run);
  }
  ex.run(cameras, eo);
  run.wall_ms = ms_since(t_run) - run.peer_wait_ms;
  run.peak_rss_mb = peak_resident_mb();
  run.faults_injected = tiles.injected_faults();
  run.faults_survived = tiles.failed_tiles();  // the run went on past every one
  return run;
}

// Frames over twice their in-memory time, or (without one) over twice the
// median of the 21 frames around them.
int stall_frames(const std::vector<double>& ms, const std::vector<double>& mem) {
  int n = 0;
  for (std::size_t i = 0; i < ms.size(); ++i) {
    double ref;
    if (!mem.empty()) {
      ref = mem[i];
    } else {
      const std::size_t a = i >= 10 ? i - 10 : 0, b = std::min(ms.size(), i + 11);
      ref = median(
          std::vector<double>(ms.begin() + std::ptrdiff_t(a), ms.begin() + std::ptrdiff_t(b)));
    }
    n += ms[i] > 2 * ref;
  }
  return n;
}

void write_plot(const OutputDir& out, const StreamRun& run, const std::vector<double>& mem) {
  std::ofstream dat(out.file("stream_frames.dat"));
  dat << "# frame stream_ms in_memory_ms degraded_samples\n";
  for (std::size_t i = 0; i < run.frames.size(); ++i)
    dat << i << ' ' << run.frames[i].ms << ' ' << (mem.empty() ? NAN : mem[i]) << ' '
        << run.frames[i].st.degraded_samples << '\n';
  dat.close();
  std::ofstream gp(out.file("stream_frames.gp"));
  gp << "set terminal pngcairo size 1000,700\nset output 'stream_frames.png'\nset multiplot layout "
        "2,1\n"
     << "set grid\nset ylabel 'ms per frame'\nplot 'stream_frames.dat' using 1:2 with lines title "
        "'streamed', '' using 1:3 with lines title 'in memory'\n"
     << "set xlabel 'frame along the path'\nset ylabel 'log10(1 + degraded reads)'\n"
        "plot 'stream_frames.dat' using 1:(log10(1 + $4)) with impulses title 'degraded reads'\n"
        "unset multiplot\n";
  gp.close();
  const std::string error = run_gnuplot(out.partial().string(), "stream_frames.gp");
  if (!error.empty())
    fmt::print(stderr, "warning: {}; stream_frames.dat kept without a plot\n", error);
}

nlohmann::json summary_json(const BenchStreamOpts& o, const TileSetInfo& set, const StreamRun& run,
                            int w, int h) {
  const std::vector<double>& mem_ms = run.in_memory_ms;
  std::vector<double> ms;
  long long degraded = 0, degraded_late = 0, lookups = 0, misses = 0, bytes = 0;
  long long lookups_late = 0, misses_late = 0;
  for (std::size_t i = 0; i < run.frames.size(); ++i) {
    const PerFrame& f = run.frames[i];
    ms.push_back(f.ms);
    degraded += f.st.degraded_samples;
    if (i >= 30) {
      degraded_late += f.st.degraded_samples;
      lookups_late += f.st.lookups;
      misses_late += f.st.misses;
    }
    lookups += f.st.lookups;
    misses += f.st.misses;
    bytes += f.st.bytes_read;
  }
  const Summary s = summarize(ms);
  const double late_pixels =
      double(w) * h * double(std::max<std::size_t>(1, ms.size() > 30 ? ms.size() - 30 : 0));
  nlohmann::json in_memory = nullptr;
  int compared = 0, equal = 0;
  if (!mem_ms.empty()) {
    const Summary m = summarize(mem_ms);
    in_memory = {{"median_ms", m.median},
                 {"p99_ms", m.p99},
                 {"peak_rss_mb", run.in_memory_peak_rss_mb},
                 {"method",
                  "another process, in lockstep: each frame drawn right after the "
                  "streamed one"}};
    for (std::size_t i = 0; i < run.frames.size(); ++i)
      if (run.frames[i].st.degraded_samples == 0) {
        ++compared;
        equal += run.in_memory_hash[i] == run.frames[i].hash;
      }
  }
  return {
      {"terrain",
       {{"samples", {set.grid.width, set.grid.height}},
        {"bytes_on_disk", set.bytes_on_disk},
        {"levels", set.grid.coarsest_level + 1},
        {"tile_cells", 1 << set.grid.tile_log2}}},
      {"tiles", o.tiles.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.tiles)},
      {"cog", set.cog ? nlohmann::json({{"file", o.cog},
                                        {"texture", o.texture.empty() ? nlohmann::json(nullptr)
                                                                      : nlohmann::json(o.texture)},
                                        {"bounds_ms", set.cog->bounds_ms},
                                        {"bounds_cached", set.cog->bounds_cached},
                                        {"bound_levels_held_from", set.cog->bound_from}})
                      : nlohmann::json(nullptr)},
      {"cache_mb", o.cache_mb},
      {"io_threads", o.io_threads},
      {"size", {w, h}},
      {"path", o.path},
      {"frames", int(ms.size())},
      {"stream",
       {{"median_ms", s.median},
        {"p99_ms", s.p99},
        {"stall_frames", stall_frames(ms, mem_ms)},
        {"degraded_samples_total", degraded},
        {"degraded_fraction_after_warmup", double(degraded_late) / late_pixels},
        {"hit_rate", lookups ? 1.0 - double(misses) / double(lookups) : 1.0},
        {"hit_rate_after_warmup",
         lookups_late ? 1.0 - double(misses_late) / double(lookups_late) : 1.0},
        {"io_mb_s", double(bytes) / 1e6 / std::max(run.wall_ms / 1e3, 1e-9)},
        {"bytes_read_mb", double(bytes) / 1e6},
        {"peak_rss_mb", run.peak_rss_mb},
        {"pinned_mb", double(run.pinned_bytes) / (1 << 20)},
        {"first_frame_ms", run.first_frame_ms},
        {"first_frame_parts_ms",
         {{"open", run.open_ms},
          {"path", run.path_ms},
          {"pinned_levels", run.pinned_ms},
          {"first_view", run.first_view_ms}}},
        {"first_view",
         {{"max_wait_ms", o.first_view_ms},
          {"tiles_missed", run.first_view.waited_for},
          {"still_missing", run.first_view.still_missing}}},
        {"first_frame_method",
         "from the start of the command to the first frame shown: open, then the path planned "
         "while the pinned levels load (the two overlap), then the first view (an unshown draw "
         "at frame 0's camera, then a wait of at most first_view.max_wait_ms for the tiles it "
         "missed), then frame 0; the in-memory peer's load is not counted"}}},
      {"in_memory", in_memory},
      {"ratio_median",
       mem_ms.empty()
           ? nlohmann::json(nullptr)
           : nlohmann::json(s.median / std::max(in_memory["median_ms"].get<double>(), 1e-9))},
      {"images_equal_when_resident", {{"frames_compared", compared}, {"frames_equal", equal}}},
      {"faults_injected", run.faults_injected},
      {"faults_survived", run.faults_survived}};
}

nlohmann::json per_frame_json(const StreamRun& run, const std::vector<double>& mem) {
  nlohmann::json a = nlohmann::json::array();
  for (std::size_t i = 0; i < run.frames.size(); ++i) {
    const PerFrame& f = run.frames[i];
    a.push_back({{"frame", i},
                 {"ms", f.ms},
                 {"update_ms", f.update_ms},
                 {"in_memory_ms", mem.empty() ? nlohmann::json(nullptr) : nlohmann::json(mem[i])},
                 {"degraded_samples", f.st.degraded_samples},
                 {"tiles_requested", f.st.requested},
                 {"tiles_loaded", f.st.loaded},
                 {"tiles_evicted", f.st.evicted},
                 {"tiles_failed", f.st.failed},
                 {"bytes_read", f.st.bytes_read},
                 {"resident_mb", double(f.st.resident_bytes) / (1 << 20)}});
  }
  return a;
}

// Whether the in-memory half should run: "auto" when the decoded pyramid
// (about 16 bytes a sample) takes under half the memory available now.
bool want_in_memory(const BenchStreamOpts& o, const TileSetInfo& set) {
  if (o.in_memory == "yes") return true;
  if (o.in_memory == "no") return false;
  const double need = 16.0 * 4 / 3 * double(set.grid.width) * set.grid.height;
  const double avail = double(sysconf(_SC_AVPHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  return need < 0.5 * avail;
}

void run(const BenchStreamOpts& o) {
  const auto t_start = Clock::now();
  auto [w, h] = parse_size(o.size, "--size");
  if (o.frames < 1 || o.frames > 100000)
    throw InputError(fmt::format("--frames {}: must be between 1 and 100000", o.frames));
  if (o.first_view_ms < 0 || o.first_view_ms > 60000)
    throw InputError(
        fmt::format("--first-view-ms {}: must be between 0 and 60000", o.first_view_ms));
  if (o.cache_mb < 1 || o.cache_mb > 1 << 20)
    throw InputError(fmt::format("--cache-mb {}: must be between 1 and 1048576", o.cache_mb));
  const bool child = o.child;
  const std::string out_dir = o.out.empty() ? std::string("out/bench_stream") : o.out;
  if (!child) check_outputs(out_dir, {o.json});
  const TileSetInfo set = open_tile_source(o.tiles, o.cog, o.texture);
  const double open_ms = ms_since(t_start);
  if (child) {
    const std::vector<Camera> path = make_path(o.path, path_proxy(set), o.frames, double(w) / h);
    return run_in_memory_child(o, set, w, h, path);
  }
  // The coarse levels are pinned (read) while the path is planned: both come
  // before the first frame, and they use different cores and GDAL handles.
  double pinned_ms = 0;
  auto opening = std::async(std::launch::async, [&, t0 = Clock::now()] {
    auto tiles = std::make_unique<StreamingTiles>(set, stream_options(o, h));
    pinned_ms = ms_since(t0);
    return tiles;
  });
  std::vector<Camera> path;
  try {
    path = make_path(o.path, path_proxy(set), o.frames, double(w) / h);
  } catch (...) {
    opening.wait();  // never leave the opening thread running past its captures
    throw;
  }
  const double path_ms = ms_since(t_start) - open_ms;
  const std::unique_ptr<StreamingTiles> tiles = opening.get();
  const double ready_ms = ms_since(t_start);  // open + the longer of path and pinned levels
  OutputDir out(out_dir, output_policy());
  // The in-memory peer loads its terrain before the streamed frames start, so
  // its load never competes with the streamed run's first frame.
  std::optional<InMemoryPeer> peer;
  if (want_in_memory(o, set)) peer.emplace(o);
  const auto t_run = Clock::now();
  StreamRun run = run_streamed(o, *tiles, t_run, w, h, path, peer && peer->ok() ? &*peer : nullptr);
  run.open_ms = open_ms;
  run.path_ms = path_ms;
  run.pinned_ms = pinned_ms;
  run.first_frame_ms += ready_ms;  // time to first frame: from the start, less the peer's load
  if (peer) run.in_memory_peak_rss_mb = peer->peak_rss_mb();
  if (run.in_memory_ms.size() != run.frames.size()) {  // the peer died part way: no comparison
    run.in_memory_ms.clear();
    run.in_memory_hash.clear();
  }
  const std::vector<double>& mem_ms = run.in_memory_ms;
  write_plot(out, run, mem_ms);
  nlohmann::json j = summary_json(o, set, run, w, h);
  nlohmann::json full = j;
  full["per_frame"] = per_frame_json(run, mem_ms);
  write_json(full, out.file("bench_stream.json"));  // JSON last: the directory is complete
  out.commit();
  if (!o.json.empty()) write_json(full, o.json);
  fmt::print("{}\n", j.dump(2));
}

}  // namespace

void add_bench_stream(CLI::App& bench) {
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
  cmd->add_option("--path", o->path, "'low-fast' (default), 'paper' or a JSON path file");
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
  cmd->add_option("--json", o->json, "also write the JSON here");
  cmd->add_option("--out", o->out, "output directory: plot, JSON (default out/bench_stream)");
  cmd->callback([o] { run(*o); });
}

}  // namespace terrasprite::cli
