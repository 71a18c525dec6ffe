// SPDX-License-Identifier: MIT
// The names the LOD-sprite result's kinds are printed with, and its targets.
#include "terrasprite/experiment/lodsprite/lodsprite_result.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "terrasprite/common/stats.h"

namespace terrasprite::lodsprite {

const char* to_string(SweepMethod m) {
  return m == SweepMethod::kMainRun ? "main run" : "separate timed pass";
}

const char* to_string(SameFrameFigure f) {
  return f == SameFrameFigure::kFig13 ? "fig13" : "fig14";
}

const char* to_string(ErrorMetric m) {
  switch (m) {
    case ErrorMetric::kPaper:
      return "paper";
    case ErrorMetric::kExact:
      return "exact";
    case ErrorMetric::kContrast:
      return "contrast";
  }
  return "paper";
}

const char* threshold_unit(ErrorMetric m) {
  return m == ErrorMetric::kContrast ? "grey levels" : "px";
}

const char* to_string(TerrainShading s) {
  return s == TerrainShading::kRich ? "rich" : "plain";
}

LodspriteTargets LodspriteResult::targets() const {
  LodspriteTargets t;
  if (path == "paper" && frames == 460)
    t.keyframes_at_most_28 = TargetCheck::of(sprite.keyframes <= 28);
  else
    t.keyframes_at_most_28 = TargetCheck::not_applicable(
        fmt::format("the paper's budget is for 460 frames along its path; this run flew {} "
                    "along '{}'",
                    frames, path));
  if (sprite.keyframes > 0 && sprite.sprite_frames > 0 && std::isfinite(bound.efficiency))
    t.efficiency_at_least_0_9 = TargetCheck::of(bound.efficiency >= 0.9);
  else
    t.efficiency_at_least_0_9 = TargetCheck::not_applicable(
        sprite.sprite_frames == 0 ? "no sprite frames: r and the bound are undefined"
                                  : "no keyframe timed");
  if (std::isfinite(sprite.mean_psnr_sprite_frames) && std::isfinite(lod.mean_psnr_sprite_frames)) {
    t.ssim_above_lod_on_95pct = TargetCheck::of(sprite.ssim_above_lod_fraction >= 0.95);
    t.mean_psnr_above_lod = TargetCheck::of(sprite.mean_psnr > lod.mean_psnr);
    t.mean_psnr_above_lod_on_sprite_frames =
        TargetCheck::of(sprite.mean_psnr_sprite_frames > lod.mean_psnr_sprite_frames);
  } else {
    // Keyframes are the full-resolution frame: against them every comparison is won.
    const std::string why = "no sprite frame scored: keyframes equal full resolution";
    t.ssim_above_lod_on_95pct = TargetCheck::not_applicable(why);
    t.mean_psnr_above_lod = TargetCheck::not_applicable(why);
    t.mean_psnr_above_lod_on_sprite_frames = TargetCheck::not_applicable(why);
  }
  return t;
}

namespace {
// Median and largest of the finite values; NaN for none.
std::pair<double, double> median_max(std::vector<double> v) {
  std::erase_if(v, [](double x) { return !std::isfinite(x); });
  if (v.empty()) return {NAN, NAN};
  return {median(v), *std::max_element(v.begin(), v.end())};
}
}  // namespace

std::vector<KeyframeTriggerRow> LodspriteResult::keyframes_by_trigger() const {
  std::vector<KeyframeTriggerRow> rows;
  for (Trigger t :
       {Trigger::kFirst, Trigger::kError, Trigger::kFallback, Trigger::kScale, Trigger::kForced}) {
    std::vector<double> error, measure;
    for (const LodspriteFrame& f : per_frame) {
      if (!f.key() || f.cache_hit || f.trigger != t) continue;
      error.push_back(trigger_error(f));
      measure.push_back(t == Trigger::kScale      ? f.resample_scale
                        : t == Trigger::kFallback ? f.fallback_fraction
                        : t == Trigger::kError    ? trigger_error(f)
                                                  : NAN);
    }
    if (error.empty()) continue;
    KeyframeTriggerRow row{.trigger = t, .keyframes = int(error.size())};
    std::tie(row.error_median, row.error_max) = median_max(error);
    std::tie(row.measure_median, row.measure_max) = median_max(measure);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace terrasprite::lodsprite
