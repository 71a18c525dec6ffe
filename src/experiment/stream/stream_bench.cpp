// SPDX-License-Identifier: MIT
// The streaming study (terrasprite/experiment/stream.h): open the tile set,
// pin its coarse levels while the path is planned, fly the streamed frames
// (the in-memory peer drawing each one after them), then the figures.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <future>
#include <memory>
#include <optional>
#include <tuple>

#include "in_memory_peer.h"
#include "stream/cog_source.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/elapsed.h"
#include "terrasprite/common/process_memory.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/experiment/stream.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite {
namespace {

using stream_bench::ChildReply;
using stream_bench::InMemoryPeer;
using Clock = std::chrono::steady_clock;

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

// What the streamed run gathered, frame by frame, before the figures.
struct StreamRun {
  std::vector<StreamFrame> frames;
  std::vector<std::pair<int, Image>> snapshots;
  std::vector<std::uint64_t> hash;
  std::vector<double> in_memory_ms;
  std::vector<std::uint64_t> in_memory_hash;
  double first_frame_ms = 0, wall_ms = 0, peak_rss_mb = 0, first_view_ms = 0;
  StreamingTiles::FirstView first_view;
  double peer_wait_ms = 0;  ///< waiting for the peer's frames: not the streamed run's time
};

// What came before the first frame: the open tile cache and the path.
struct Opened {
  TileSetInfo set;
  std::unique_ptr<StreamingTiles> tiles;
  std::vector<Camera> path;
  double open_ms = 0, path_ms = 0, pinned_ms = 0, ready_ms = 0;
  std::size_t pinned_bytes = 0;  ///< the pinned levels, held for the whole run
};

StreamOptions stream_options(const StreamBenchOptions& o) {
  StreamOptions so;
  so.cache_bytes = std::size_t(o.cache_mb) << 20;
  so.io_threads = o.io_threads;
  so.image_height = o.height;
  return so;
}

// The coarse levels are pinned (read) while the path is planned: both come
// before the first frame, and they use different cores and GDAL handles.
Opened open_source(const StreamBenchOptions& o, Clock::time_point t_start) {
  Opened op;
  op.set = open_tile_source(o.tiles, o.cog, o.texture);
  op.open_ms = ms_since(t_start);
  auto opening = std::async(std::launch::async, [&, t0 = Clock::now()] {
    auto tiles = std::make_unique<StreamingTiles>(op.set, stream_options(o));
    op.pinned_ms = ms_since(t0);
    return tiles;
  });
  try {
    op.path =
        make_path(o.path, stream_bench::path_proxy(op.set), o.frames, double(o.width) / o.height);
  } catch (...) {
    opening.wait();  // never leave the opening thread running past its captures
    throw;
  }
  op.path_ms = ms_since(t_start) - op.open_ms;
  op.tiles = opening.get();
  op.pinned_bytes = op.tiles->pinned_bytes();
  op.ready_ms = ms_since(t_start);  // open + the longer of path and pinned levels
  return op;
}

// Whether the in-memory half should run: "auto" when the decoded pyramid
// (about 16 bytes a sample) takes under half the memory available now.
bool want_in_memory(const StreamBenchOptions& o, const TileSetInfo& set) {
  if (o.peer_command.empty() || o.in_memory == InMemoryRun::kNo) return false;
  if (o.in_memory == InMemoryRun::kYes) return true;
  const double need = 16.0 * 4 / 3 * double(set.grid.width) * set.grid.height;
  const double avail = double(sysconf(_SC_AVPHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  return need < 0.5 * avail;
}

// The streamed frames; `t_run` is when they begin. After each frame's timed
// span, the same frame in memory, in the peer's process.
StreamRun fly_streamed(const StreamBenchOptions& o, StreamingTiles& tiles,
                       const std::vector<Camera>& path, InMemoryPeer* peer) {
  VoxelOptions vo;
  vo.threads = o.threads;
  StreamedVoxel renderer(tiles, o.width, o.height, vo);
  StreamRun run;
  const auto t_run = Clock::now();
  Experiment ex;
  ex.add({.renderer = &renderer,
          .name = "stream",
          .warmup_draws = 0,  // the first frame is part of the figures (time to first frame)
          .annotate = [&](const Frame& f, FrameResult&) {
            if (run.frames.empty()) run.first_frame_ms = ms_since(t_run);
            run.frames.push_back({f.ms, renderer.update_ms(), std::nullopt, renderer.last()});
            run.hash.push_back(stream_bench::image_hash(f.color));
            const int i = int(run.frames.size()) - 1;
            if (i == 0 || i == (o.frames - 1) / 2 || i == o.frames - 1)
              run.snapshots.emplace_back(i, f.color);
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
  eo.progress = o.progress;
  PathSource cameras(path);
  if (o.first_view_ms > 0 && !path.empty()) {
    run.first_view =
        renderer.prime(path.front(), t_run + std::chrono::milliseconds(o.first_view_ms));
    run.first_view_ms = ms_since(t_run);
  }
  ex.run(cameras, eo);
  run.wall_ms = ms_since(t_run) - run.peer_wait_ms;
  run.peak_rss_mb = peak_resident_mb();
  return run;
}

// Frames over twice their in-memory time, or (without one) over twice the
// median of the 21 frames around them.
std::vector<bool> slow_frames(const std::vector<StreamFrame>& frames) {
  std::vector<double> ms;
  for (const StreamFrame& f : frames) ms.push_back(f.ms);
  std::vector<bool> slow(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    double ref;
    if (frames[i].in_memory_ms) {
      ref = *frames[i].in_memory_ms;
    } else {
      const std::size_t a = i >= 10 ? i - 10 : 0, b = std::min(ms.size(), i + 11);
      ref = median(
          std::vector<double>(ms.begin() + std::ptrdiff_t(a), ms.begin() + std::ptrdiff_t(b)));
    }
    slow[i] = ms[i] > 2 * ref;
  }
  return slow;
}

// Whether the cache streamed in this frame: a lookup missed, or tiles came or went.
bool streamed_in(const StreamFrameStats& st) {
  return st.misses > 0 || st.loaded > 0 || st.evicted > 0 || st.failed > 0;
}

// Frame time, reads and hit rates over the run and after its warm-up frames.
StreamSummary stream_summary(const StreamRun& run, const Opened& op, const StreamBenchOptions& o) {
  std::vector<double> ms;
  long long degraded = 0, lookups = 0, misses = 0, bytes = 0;
  long long lookups_late = 0, misses_late = 0;
  for (std::size_t i = 0; i < run.frames.size(); ++i) {
    const StreamFrameStats& st = run.frames[i].stats;
    ms.push_back(run.frames[i].ms);
    degraded += st.degraded_samples;
    if (i >= std::size_t(kStreamWarmupFrames)) {
      lookups_late += st.lookups;
      misses_late += st.misses;
    }
    lookups += st.lookups;
    misses += st.misses;
    bytes += st.bytes_read;
  }
  const Summary s = summarize(ms);
  StreamSummary out;
  out.median_ms = s.median;
  out.p99_ms = s.p99;
  out.degraded_samples_total = degraded;
  out.degraded_fraction_after_warmup = degraded_fraction_after_warmup(run.frames);
  out.hit_rate = lookups ? 1.0 - double(misses) / double(lookups) : 1.0;
  out.hit_rate_after_warmup = lookups_late ? 1.0 - double(misses_late) / double(lookups_late) : 1.0;
  out.io_mb_s = double(bytes) / 1e6 / std::max(run.wall_ms / 1e3, 1e-9);
  out.bytes_read_mb = double(bytes) / 1e6;
  out.peak_rss_mb = run.peak_rss_mb;
  out.pinned_mb = double(op.pinned_bytes) / (1 << 20);
  // Time to first frame: from the start, less the peer's load.
  out.first_frame_ms = run.first_frame_ms + op.ready_ms;
  out.open_ms = op.open_ms;
  out.path_ms = op.path_ms;
  out.pinned_ms = op.pinned_ms;
  out.first_view_ms = run.first_view_ms;
  out.first_view_max_wait_ms = o.first_view_ms;
  out.first_view_tiles_missed = run.first_view.waited_for;
  out.first_view_still_missing = run.first_view.still_missing;
  return out;
}

StreamSourceInfo source_info(const StreamBenchOptions& o, const TileSetInfo& set) {
  StreamSourceInfo s;
  s.samples_x = set.grid.width;
  s.samples_y = set.grid.height;
  s.bytes_on_disk = set.bytes_on_disk;
  s.levels = set.grid.coarsest_level + 1;
  s.tile_cells = 1 << set.grid.tile_log2;
  s.tiles = o.tiles;
  if (set.cog)
    s.cog = StreamSourceInfo::Cog{o.cog, o.texture, set.cog->bounds_ms, set.cog->bounds_cached,
                                  set.cog->bound_from};
  return s;
}

// The in-memory half's figures, when the peer answered every frame: its
// times and the images compared where the streamed frame read no coarser data.
void add_in_memory(StreamBenchResult& res, StreamRun& run, double peer_peak_rss_mb) {
  if (run.in_memory_ms.empty()) return;
  const Summary m = summarize(run.in_memory_ms);
  res.in_memory = InMemorySummary{m.median, m.p99, peer_peak_rss_mb};
  res.ratio_median = res.stream.median_ms / std::max(m.median, 1e-9);
  for (std::size_t i = 0; i < run.frames.size(); ++i) {
    run.frames[i].in_memory_ms = run.in_memory_ms[i];
    if (run.frames[i].stats.degraded_samples == 0) {
      ++res.frames_compared;
      res.frames_equal += run.in_memory_hash[i] == run.hash[i];
    }
  }
}

// Stalls make a run fall behind; degraded reads past the warm-up make it coarse.
StreamVerdict judge(const StreamSummary& s) {
  if (s.stall_frames > 0) return StreamVerdict::kFellBehind;
  if (s.degraded_fraction_after_warmup > 0.01) return StreamVerdict::kDegraded;
  return StreamVerdict::kKeptUp;
}

}  // namespace

const char* to_string(StreamVerdict v) {
  switch (v) {
    case StreamVerdict::kKeptUp:
      return "kept up";
    case StreamVerdict::kDegraded:
      return "served coarser data";
    case StreamVerdict::kFellBehind:
      return "fell behind";
  }
  return "kept up";
}

std::pair<int, int> stall_frames(const std::vector<StreamFrame>& frames) {
  const std::vector<bool> slow = slow_frames(frames);
  int stalls = 0, noise = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (!slow[i]) continue;
    (streamed_in(frames[i].stats) ? stalls : noise) += 1;
  }
  return {stalls, noise};
}

double degraded_fraction_after_warmup(const std::vector<StreamFrame>& frames) {
  long long degraded = 0, lookups = 0;
  for (std::size_t i = kStreamWarmupFrames; i < frames.size(); ++i) {
    degraded += frames[i].stats.degraded_samples;
    lookups += frames[i].stats.lookups;
  }
  if (frames.size() <= std::size_t(kStreamWarmupFrames)) return NAN;
  return lookups > 0 ? double(degraded) / double(lookups) : 0.0;
}

StreamBenchResult run_stream_bench(const StreamBenchOptions& o) {
  const Opened op = open_source(o, Clock::now());
  // The in-memory peer loads its terrain before the streamed frames start, so
  // its load never competes with the streamed run's first frame.
  std::optional<InMemoryPeer> peer;
  if (want_in_memory(o, op.set)) peer.emplace(o.peer_command);
  StreamRun run = fly_streamed(o, *op.tiles, op.path, peer && peer->ok() ? &*peer : nullptr);
  if (run.in_memory_ms.size() != run.frames.size()) {  // the peer died part way: no comparison
    run.in_memory_ms.clear();
    run.in_memory_hash.clear();
  }
  StreamBenchResult res;
  res.source = source_info(o, op.set);
  res.cache_mb = o.cache_mb;
  res.io_threads = o.io_threads;
  res.width = o.width;
  res.height = o.height;
  res.path = o.path;
  res.stream = stream_summary(run, op, o);
  res.ratio_median = NAN;
  add_in_memory(res, run, peer ? peer->peak_rss_mb() : 0);
  res.faults_injected = op.tiles->injected_faults();
  res.faults_survived = op.tiles->failed_tiles();  // the run went on past every one
  res.frames = std::move(run.frames);
  std::tie(res.stream.stall_frames, res.stream.slow_frames_without_streaming) =
      stall_frames(res.frames);
  res.verdict = judge(res.stream);
  res.snapshots = std::move(run.snapshots);
  return res;
}

void run_stream_peer(const StreamBenchOptions& o) {
  const TileSetInfo set = open_tile_source(o.tiles, o.cog, o.texture);
  const std::vector<Camera> path =
      make_path(o.path, stream_bench::path_proxy(set), o.frames, double(o.width) / o.height);
  stream_bench::run_in_memory_child(set, o.width, o.height, o.threads, o.first_view_ms > 0, path);
}

}  // namespace terrasprite
