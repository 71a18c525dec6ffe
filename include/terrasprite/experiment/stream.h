// SPDX-License-Identifier: MIT
// The streaming study (`bench stream`): a flythrough over a tiled terrain
// read through the streaming tile cache (load on demand, prefetch, never
// wait), then the same frames with the whole terrain in memory in a separate
// process (so its memory does not count against the streamed run), compared
// frame by frame: time, stalls, degraded reads and identical images once
// tiles are resident. Every figure is computed here; the report prints them.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "terrasprite/stream/streaming_tiles.h"

namespace terrasprite {

/// Whether the in-memory half runs.
enum class InMemoryRun {
  kAuto,  ///< when the decoded pyramid takes under half the memory available now
  kYes,
  kNo,
};

struct StreamBenchOptions {
  /// The terrain: a tile directory (`terrasprite tile --out`), or an existing
  /// COG with an optional RGB texture of the same size (then `tiles` is empty).
  std::string tiles, cog, texture;
  int cache_mb = 256;  ///< tile cache budget, MiB, 1..2^20
  int io_threads = 2;
  int width = 1920, height = 1080;  ///< pixels
  std::string path = "low-fast";    ///< make_path's spec, planned over a coarse level
  int frames = 300;                 ///< 1..100000
  int threads = 0;                  ///< ray-caster threads; 0: all
  /// Before frame 0, wait at most this long (0..60000 ms) for the tiles its
  /// view reads; 0: draw frame 0 from whatever is resident.
  int first_view_ms = 600;
  InMemoryRun in_memory = InMemoryRun::kAuto;
  /// The command that starts this program as the in-memory peer (argv[0] is
  /// the executable; see run_stream_peer); empty: no in-memory half.
  std::vector<std::string> peer_command;
  std::function<void(int done, int total)> progress;
};

/// One streamed frame.
struct StreamFrame {
  double ms = 0;                       ///< the draw, the cache's update included
  double update_ms = 0;                ///< the cache's update alone
  std::optional<double> in_memory_ms;  ///< the same frame in memory, when compared
  StreamFrameStats stats;
};

/// The tile set as opened.
struct StreamSourceInfo {
  int samples_x = 0, samples_y = 0;
  long long bytes_on_disk = 0;
  int levels = 0, tile_cells = 0;
  std::string tiles;  ///< the tile directory; empty for a COG
  struct Cog {
    std::string file, texture;  ///< texture: empty when none
    double bounds_ms = 0;
    bool bounds_cached = false;
    int bound_levels_held_from = 0;
  };
  std::optional<Cog> cog;
};

/// Frames before this one are the warm-up: the cache fills; the "after
/// warm-up" figures leave them out.
inline constexpr int kStreamWarmupFrames = 30;

/// The streamed run's figures.
struct StreamSummary {
  double median_ms = 0, p99_ms = 0;
  /// Stall: a slow frame (over twice its in-memory time, or without one over
  /// twice the median of the 21 frames around it) in which the cache streamed
  /// (a tile missed, loaded or evicted). Slow frames with no streaming in them
  /// are this machine's noise: slow_frames_without_streaming.
  int stall_frames = 0;
  int slow_frames_without_streaming = 0;
  long long degraded_samples_total = 0;
  /// Of the height reads from frame kStreamWarmupFrames on, the share served
  /// coarser than the march asked (0..1); NaN when the run is no longer than
  /// the warm-up.
  double degraded_fraction_after_warmup = 0;
  double hit_rate = 1, hit_rate_after_warmup = 1;
  double io_mb_s = 0, bytes_read_mb = 0;
  double peak_rss_mb = 0, pinned_mb = 0;
  /// From the start of run_stream_bench to the first frame shown, and its
  /// parts: open, the path (overlapping the pinned levels' load), the first
  /// view (an unshown draw, then the wait for its tiles).
  double first_frame_ms = 0;
  double open_ms = 0, path_ms = 0, pinned_ms = 0, first_view_ms = 0;
  int first_view_max_wait_ms = 0;
  int first_view_tiles_missed = 0, first_view_still_missing = 0;
};

/// The one-line judgement of a streamed run.
enum class StreamVerdict {
  kKeptUp,      ///< no stall frame, at most 1% of reads degraded after the warm-up
  kDegraded,    ///< no stall frame, but over 1% of reads degraded after the warm-up
  kFellBehind,  ///< stall frames
};
/// "kept up", "served coarser data", "fell behind".
const char* to_string(StreamVerdict v);

/// Counts a run's stall frames and its slow frames without streaming (see
/// StreamSummary), from each frame's time, in-memory time and cache stats.
/// Every frame needs in_memory_ms, or none does.
std::pair<int, int> stall_frames(const std::vector<StreamFrame>& frames);
/// StreamSummary::degraded_fraction_after_warmup of these frames.
double degraded_fraction_after_warmup(const std::vector<StreamFrame>& frames);

struct InMemorySummary {
  double median_ms = 0, p99_ms = 0, peak_rss_mb = 0;
};

struct StreamBenchResult {
  StreamSourceInfo source;
  int cache_mb = 0, io_threads = 0;
  int width = 0, height = 0;
  std::string path;
  StreamSummary stream;
  /// Set when the in-memory peer answered every frame.
  std::optional<InMemorySummary> in_memory;
  double ratio_median = 0;  ///< streamed / in-memory median; NaN without the peer
  /// Frames with no degraded read, and of those, the ones whose image equals
  /// the in-memory one (0 and 0 without the peer).
  int frames_compared = 0, frames_equal = 0;
  int faults_injected = 0, faults_survived = 0;
  StreamVerdict verdict = StreamVerdict::kKeptUp;
  std::vector<StreamFrame> frames;
  /// A few streamed images (the first, middle and last frames), by frame number.
  std::vector<std::pair<int, Image>> snapshots;
};

/// Runs the study. Throws InputError naming the tile source when it cannot
/// be read, or for a bad path spec. A peer that fails to start or dies part
/// way prints one warning on stderr and leaves the in-memory half out.
StreamBenchResult run_stream_bench(const StreamBenchOptions& options);

/// The in-memory peer's whole life, in the process `peer_command` started:
/// loads the terrain into memory, answers "ready" on fd 4, then draws frame i
/// of the path each time the parent asks (frame numbers on fd 3, answers on
/// fd 4) until the parent closes the pipe. `options` as the parent's.
void run_stream_peer(const StreamBenchOptions& options);

}  // namespace terrasprite
