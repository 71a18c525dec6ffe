// SPDX-License-Identifier: MIT
#include "experiment/lodsprite/trigger_comparison.h"

#include <cmath>
#include <cstdlib>

#include "experiment/lodsprite/sprite_pass.h"

namespace terrasprite::lodsprite {
namespace {

TriggerSide side(const SpriteOptions& o, const PassResult& p) {
  return {.metric = o.metric,
          .threshold = o.threshold_px,
          .keyframes = p.keyframes,
          .mean_ssim = p.mean_ssim,
          .mean_psnr = p.mean_psnr,
          .min_ssim = p.min_ssim};
}

}  // namespace

TriggerComparison compare_triggers(Scene& scene, std::span<const Camera> path, int w, int h,
                                   const SpriteOptions& with_all, const std::vector<Image>& refs,
                                   int every) {
  TriggerComparison t;
  // The error triggers alone: the others (scale, fallback) would spend
  // keyframes of their own on both sides and blur the comparison.
  SpriteOptions main = with_all;
  main.max_resample_scale = INFINITY;
  main.max_fallback_fraction = 1.0;
  const int want = simulate_keyframes(scene, path, w, h, main);
  SpriteOptions other = main;
  other.metric =
      main.metric == ErrorMetric::kContrast ? ErrorMetric::kPaper : ErrorMetric::kContrast;
  // Keyframes fall as the threshold rises: bisect log(threshold) over a
  // range wide enough for both units (0.01 px .. 1000 grey levels).
  double lo = std::log(0.01), hi = std::log(1000.0);
  double best = std::exp(0.5 * (lo + hi));
  int best_gap = -1, best_count = 0;
  for (int i = 0; i < 24 && best_gap != 0; ++i) {
    const double mid = 0.5 * (lo + hi);
    other.threshold_px = std::exp(mid);
    const int count = simulate_keyframes(scene, path, w, h, other);
    ++t.simulations;
    const int gap = std::abs(count - want);
    if (best_gap < 0 || gap < best_gap || (gap == best_gap && count < best_count)) {
      best_gap = gap;
      best_count = count;
      best = other.threshold_px;
    }
    (count > want ? lo : hi) = mid;
  }
  other.threshold_px = best;
  t.main = side(main, sprite_pass(scene, path, w, h, main, refs, every));
  t.other = side(other, sprite_pass(scene, path, w, h, other, refs, every));
  return t;
}

}  // namespace terrasprite::lodsprite
