// SPDX-License-Identifier: MIT
#include "terrasprite/report/stream_report.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::report {
namespace {

nlohmann::json or_null(const std::string& s) {
  return s.empty() ? nlohmann::json(nullptr) : nlohmann::json(s);
}

nlohmann::json cog_json(const StreamSourceInfo& s) {
  if (!s.cog) return nullptr;
  return {{"file", s.cog->file},
          {"texture", or_null(s.cog->texture)},
          {"bounds_ms", s.cog->bounds_ms},
          {"bounds_cached", s.cog->bounds_cached},
          {"bound_levels_held_from", s.cog->bound_levels_held_from}};
}

nlohmann::json streamed_json(const StreamSummary& s) {
  return {{"median_ms", s.median_ms},
          {"p99_ms", s.p99_ms},
          {"stall_frames", s.stall_frames},
          {"slow_frames_without_streaming", s.slow_frames_without_streaming},
          {"degraded_samples_total", s.degraded_samples_total},
          {"degraded_fraction_after_warmup", number_or_null(s.degraded_fraction_after_warmup)},
          {"hit_rate", s.hit_rate},
          {"hit_rate_after_warmup", s.hit_rate_after_warmup},
          {"io_mb_s", s.io_mb_s},
          {"bytes_read_mb", s.bytes_read_mb},
          {"peak_rss_mb", s.peak_rss_mb},
          {"pinned_mb", s.pinned_mb},
          {"first_frame_ms", s.first_frame_ms},
          {"first_frame_parts_ms",
           {{"open", s.open_ms},
            {"path", s.path_ms},
            {"pinned_levels", s.pinned_ms},
            {"first_view", s.first_view_ms}}},
          {"first_view",
           {{"max_wait_ms", s.first_view_max_wait_ms},
            {"tiles_missed", s.first_view_tiles_missed},
            {"still_missing", s.first_view_still_missing}}},
          {"first_frame_method",
           "from the start of the command to the first frame shown: open, then the path planned "
           "while the pinned levels load (the two overlap), then the first view (an unshown draw "
           "at frame 0's camera, then a wait of at most first_view.max_wait_ms for the tiles it "
           "missed), then frame 0; the in-memory peer's load is not counted"}};
}

nlohmann::json in_memory_json(const std::optional<InMemorySummary>& m) {
  if (!m) return nullptr;
  return {{"median_ms", m->median_ms},
          {"p99_ms", m->p99_ms},
          {"peak_rss_mb", m->peak_rss_mb},
          {"method",
           "another process, in lockstep: each frame drawn right after the "
           "streamed one"}};
}

}  // namespace

nlohmann::json stream_bench_json(const StreamBenchResult& r) {
  const StreamSourceInfo& s = r.source;
  return {{"terrain",
           {{"samples", {s.samples_x, s.samples_y}},
            {"bytes_on_disk", s.bytes_on_disk},
            {"levels", s.levels},
            {"tile_cells", s.tile_cells}}},
          {"tiles", or_null(s.tiles)},
          {"cog", cog_json(s)},
          {"cache_mb", r.cache_mb},
          {"io_threads", r.io_threads},
          {"size", {r.width, r.height}},
          {"path", r.path},
          {"frames", int(r.frames.size())},
          {"stream", streamed_json(r.stream)},
          {"in_memory", in_memory_json(r.in_memory)},
          {"ratio_median", r.in_memory ? nlohmann::json(r.ratio_median) : nlohmann::json(nullptr)},
          {"images_equal_when_resident",
           {{"frames_compared", r.frames_compared}, {"frames_equal", r.frames_equal}}},
          {"faults_injected", r.faults_injected},
          {"faults_survived", r.faults_survived},
          {"verdict", to_string(r.verdict)},
          {"definitions", stream_definitions_json()}};
}

nlohmann::json stream_definitions_json() {
  const std::string warm = std::to_string(kStreamWarmupFrames);
  return {{"median_ms", "median streamed frame time: the draw, the cache's update included"},
          {"p99_ms", "99th percentile of the streamed frame times"},
          {"stall_frames",
           "frames over twice their in-memory time (without the in-memory run: over twice the "
           "median of the 21 frames around them) in which the cache streamed: a tile lookup "
           "missed, or tiles were loaded, evicted or failed"},
          {"slow_frames_without_streaming",
           "frames as slow as a stall but with no streaming in them: timing noise of this machine"},
          {"degraded_samples_total",
           "height reads over the run served from a coarser level than the ray march asked"},
          {"degraded_fraction_after_warmup",
           "of the height reads from frame " + warm +
               " on, the share served coarser than asked (0..1); null when the run has no frame "
               "past frame " +
               warm},
          {"hit_rate", "tile lookups that found their tile resident, over all lookups (0..1)"},
          {"hit_rate_after_warmup", "the same from frame " + warm + " on"},
          {"io_mb_s", "tile bytes decoded from disk per second of the streamed run"},
          {"peak_rss_mb", "the streaming process's peak resident memory"},
          {"first_frame_ms", "from the command's start to the first frame shown"},
          {"verdict",
           "'fell behind' with any stall frame; else 'served coarser data' when over 1% of reads "
           "after the warm-up were degraded; else 'kept up'"}};
}

std::string stream_summary_text(const StreamBenchResult& r) {
  const StreamSummary& s = r.stream;
  const std::string degraded =
      std::isfinite(s.degraded_fraction_after_warmup)
          ? fmt::format("{:.1f}% of reads degraded after frame {}",
                        100 * s.degraded_fraction_after_warmup, kStreamWarmupFrames)
          : fmt::format("degraded reads after the warm-up n/a (no frame past frame {})",
                        kStreamWarmupFrames);
  const std::string vs_memory = r.in_memory
                                    ? fmt::format(", {:.2f}x the in-memory median", r.ratio_median)
                                    : std::string(", no in-memory run to compare");
  std::string text = fmt::format(
      "bench stream: {} frames at {}x{} over {}x{} samples, {} MB cache: median {:.1f} ms, "
      "p99 {:.1f} ms{}\n",
      r.frames.size(), r.width, r.height, r.source.samples_x, r.source.samples_y, r.cache_mb,
      s.median_ms, s.p99_ms, vs_memory);
  text += fmt::format(
      "verdict: streaming {} ({} stall frames, {} slow frames without streaming; {}; tile hit "
      "rate {:.1f}%)\n",
      to_string(r.verdict), s.stall_frames, s.slow_frames_without_streaming, degraded,
      100 * s.hit_rate);
  return text;
}

std::vector<std::string> write_stream_snapshots(const StreamBenchResult& r,
                                                const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& [frame, image] : r.snapshots) {
    names.push_back(fmt::format("frame_{:04d}.png", frame));
    save_png(image, dir + "/" + names.back());
  }
  return names;
}

nlohmann::json stream_per_frame_json(const StreamBenchResult& r) {
  nlohmann::json a = nlohmann::json::array();
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    const StreamFrame& f = r.frames[i];
    a.push_back({{"frame", i},
                 {"ms", f.ms},
                 {"update_ms", f.update_ms},
                 {"in_memory_ms",
                  f.in_memory_ms ? nlohmann::json(*f.in_memory_ms) : nlohmann::json(nullptr)},
                 {"degraded_samples", f.stats.degraded_samples},
                 {"tiles_requested", f.stats.requested},
                 {"tiles_loaded", f.stats.loaded},
                 {"tiles_evicted", f.stats.evicted},
                 {"tiles_failed", f.stats.failed},
                 {"bytes_read", f.stats.bytes_read},
                 {"resident_mb", double(f.stats.resident_bytes) / (1 << 20)}});
  }
  return a;
}

std::string write_stream_plot(const StreamBenchResult& r, const std::string& dir) {
  std::ostringstream dat;
  dat << "# frame stream_ms in_memory_ms degraded_samples\n";
  for (std::size_t i = 0; i < r.frames.size(); ++i)
    dat << i << ' ' << r.frames[i].ms << ' ' << r.frames[i].in_memory_ms.value_or(NAN) << ' '
        << r.frames[i].stats.degraded_samples << '\n';
  write_text(dir + "/stream_frames.dat", dat.str());
  write_text(dir + "/stream_frames.gp",
             "set terminal pngcairo size 1000,700\nset output 'stream_frames.png'\nset multiplot "
             "layout 2,1\n"
             "set grid\nset ylabel 'ms per frame'\nplot 'stream_frames.dat' using 1:2 with lines "
             "title 'streamed', '' using 1:3 with lines title 'in memory'\n"
             "set xlabel 'frame along the path'\nset ylabel 'log10(1 + degraded reads)'\n"
             "plot 'stream_frames.dat' using 1:(log10(1 + $4)) with impulses title 'degraded "
             "reads'\n"
             "unset multiplot\n");
  return run_gnuplot(dir, "stream_frames.gp");
}

}  // namespace terrasprite::report
