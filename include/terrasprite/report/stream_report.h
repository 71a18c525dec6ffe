// SPDX-License-Identifier: MIT
// bench stream's report: the streaming study's typed result in, JSON and a
// frame-time plot out.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "terrasprite/experiment/stream.h"

namespace terrasprite::report {

/// The bench's summary JSON: terrain, tiles, cog, cache_mb, io_threads,
/// size, path, frames, stream, in_memory, ratio_median,
/// images_equal_when_resident, faults_injected, faults_survived, verdict,
/// definitions. Figures not measured (no in-memory half, no frames past the
/// warm-up) are null.
nlohmann::json stream_bench_json(const StreamBenchResult& r);

/// What each figure of stream_bench_json's `stream` object means, by key
/// (the JSON's `definitions`; docs/streaming.md says the same).
nlohmann::json stream_definitions_json();

/// The human summary: what ran, the headline figures and a verdict line
/// ("verdict: streaming kept up ..."), a few lines ending in a newline.
std::string stream_summary_text(const StreamBenchResult& r);

/// Saves r.snapshots as `dir`/frame_NNNN.png; returns the file names.
std::vector<std::string> write_stream_snapshots(const StreamBenchResult& r, const std::string& dir);

/// One entry a frame: frame, ms, update_ms, in_memory_ms, degraded_samples,
/// tiles_requested/loaded/evicted/failed, bytes_read, resident_mb.
nlohmann::json stream_per_frame_json(const StreamBenchResult& r);

/// stream_frames.dat (per frame: streamed ms, in-memory ms, degraded reads)
/// and stream_frames.gp in `dir`, then gnuplot on it (stream_frames.png).
/// Returns "" or the run_gnuplot failure line (the .dat is kept). Throws
/// InputError when a file cannot be written.
std::string write_stream_plot(const StreamBenchResult& r, const std::string& dir);

}  // namespace terrasprite::report
