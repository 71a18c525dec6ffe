// SPDX-License-Identifier: MIT
// bench stream's figures from frames built by hand: stalls need streaming in
// the frame, fractions stay in 0..1, every figure is defined. Under a second.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "terrasprite/experiment/stream.h"
#include "terrasprite/report/stream_report.h"

namespace terrasprite {
namespace {

// `n` frames of 10 ms, each with `lookups` height reads of which `degraded` coarser.
std::vector<StreamFrame> frames(int n, long long lookups = 1000, long long degraded = 0) {
  std::vector<StreamFrame> v(static_cast<std::size_t>(n));
  for (StreamFrame& f : v) {
    f.ms = 10;
    f.stats.lookups = lookups;
    f.stats.misses = f.stats.degraded_samples = degraded;
  }
  return v;
}

TEST(StreamFigures, ASlowFrameIsAStallOnlyWhenTheCacheStreamedInIt) {
  std::vector<StreamFrame> v = frames(40);
  v[5].ms = 50;  // slow, nothing streamed: this machine's noise
  v[20].ms = 50;
  v[20].stats.loaded = 3;  // slow while tiles came in: a stall
  EXPECT_EQ(stall_frames(v), std::make_pair(1, 1));
  for (StreamFrame& f : v) f.in_memory_ms = 30;  // against the in-memory twin: none is slow
  EXPECT_EQ(stall_frames(v), std::make_pair(0, 0));
}

TEST(StreamFigures, DegradedFractionIsAShareOfReads) {
  // Many reads a pixel: the share of reads, never reads per pixel.
  EXPECT_DOUBLE_EQ(degraded_fraction_after_warmup(frames(40, 100000, 25000)), 0.25);
  EXPECT_DOUBLE_EQ(degraded_fraction_after_warmup(frames(40, 0, 0)), 0.0);
  EXPECT_TRUE(std::isnan(degraded_fraction_after_warmup(frames(kStreamWarmupFrames))));
}

TEST(StreamFigures, EveryStreamFigureIsDefinedAndTheSummaryEndsInAVerdict) {
  StreamBenchResult r;
  r.frames = frames(12);
  r.stream.degraded_fraction_after_warmup = NAN;
  r.verdict = StreamVerdict::kKeptUp;
  const nlohmann::json j = report::stream_bench_json(r);
  for (const auto& [key, value] : j["stream"].items()) {
    if (key.find("first_") == 0 || key == "bytes_read_mb" || key == "pinned_mb") continue;
    EXPECT_TRUE(j["definitions"].contains(key)) << key;
  }
  EXPECT_TRUE(j["stream"]["degraded_fraction_after_warmup"].is_null());
  EXPECT_EQ(j["verdict"], "kept up");
  const std::string text = report::stream_summary_text(r);
  EXPECT_NE(text.find("verdict: streaming kept up"), std::string::npos) << text;
  EXPECT_NE(text.find("n/a"), std::string::npos) << text;
}

}  // namespace
}  // namespace terrasprite
