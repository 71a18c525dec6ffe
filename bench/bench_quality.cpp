// SPDX-License-Identifier: MIT
// Micro-benchmarks of the quality metrics at 512x512 and 1920x1080, on 1 and 2
// threads (tbb::global_control). Targets at 1080p, 2 threads: SSIM (luma,
// Wang) under 15 ms, FLIP under 60 ms. Run: build/bench/bench_quality
// (add --benchmark_repetitions=5 --benchmark_report_aggregates_only=true on a
// noisy machine and read the medians).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "terrasprite/quality/quality.h"

namespace {

using namespace terrasprite;

// A rendered-looking pair: smooth gradients, edges, texture; the test image
// has noise and a one-pixel shift in part of it.
std::pair<Image, Image> make_pair(int w, int h) {
  Image a(w, h), b(w, h);
  std::mt19937 rng(5);
  std::normal_distribution<float> noise(0, 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float s = std::sin(0.05f * x) * std::cos(0.07f * y);
      const float v[3] = {60 + 120.0f * x / w + 40 * s, 80 + 100.0f * y / h,
                          ((x / 32 + y / 32) % 3) * 90.0f};
      for (int c = 0; c < 3; ++c) {
        a.px(x, y)[c] = static_cast<std::uint8_t>(std::clamp(v[c], 0.0f, 255.0f));
        b.px(x, y)[c] = static_cast<std::uint8_t>(std::clamp(v[c] + noise(rng), 0.0f, 255.0f));
      }
      a.px(x, y)[3] = b.px(x, y)[3] = 255;
    }
  return {a, b};
}

const std::pair<Image, Image>& pair_for(int w) {
  static const auto small = make_pair(512, 512);
  static const auto hd = make_pair(1920, 1080);
  return w == 512 ? small : hd;
}

void args(benchmark::internal::Benchmark* b) {
  for (int threads : {1, 2}) {
    b->Args({512, threads});
    b->Args({1920, threads});
  }
  b->ArgNames({"width", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

template <typename F>
void run(benchmark::State& state, F metric) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(1)));
  const auto& [a, b] = pair_for(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(metric(a.view(), b.view()));
  state.SetItemsProcessed(state.iterations() * a.width * a.height);
}

void BM_SsimLuma(benchmark::State& state) {
  quality::SsimOptions o;
  o.channels = false;
  run(state, [&](const ImageView& a, const ImageView& b) { return quality::ssim(a, b, o).ssim; });
}
void BM_SsimLumaAndRgb(benchmark::State& state) {
  run(state, [](const ImageView& a, const ImageView& b) { return quality::ssim(a, b).ssim; });
}
void BM_SsimFfmpeg(benchmark::State& state) {
  quality::SsimOptions o;
  o.mode = quality::SsimMode::kFfmpeg;
  run(state, [&](const ImageView& a, const ImageView& b) { return quality::ssim(a, b, o).ssim; });
}
void BM_Flip(benchmark::State& state) {
  run(state, [](const ImageView& a, const ImageView& b) { return quality::flip(a, b).mean; });
}
void BM_Psnr(benchmark::State& state) {
  run(state, [](const ImageView& a, const ImageView& b) { return quality::psnr(a, b).rgb; });
}
void BM_Msssim(benchmark::State& state) {
  run(state, [](const ImageView& a, const ImageView& b) { return quality::msssim(a, b); });
}

BENCHMARK(BM_SsimLuma)->Apply(args);
BENCHMARK(BM_Flip)->Apply(args);
BENCHMARK(BM_SsimLumaAndRgb)->Apply(args);
BENCHMARK(BM_SsimFfmpeg)->Apply(args);
BENCHMARK(BM_Msssim)->Apply(args);
BENCHMARK(BM_Psnr)->Apply(args);

}  // namespace

BENCHMARK_MAIN();
