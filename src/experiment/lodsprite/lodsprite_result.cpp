// SPDX-License-Identifier: MIT
// The names the LOD-sprite result's kinds are printed with, and its targets.
#include "terrasprite/experiment/lodsprite/lodsprite_result.h"

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
  return {.keyframes_at_most_28 = sprite.keyframes <= 28,
          .efficiency_at_least_0_9 = bound.efficiency >= 0.9,
          .ssim_above_lod_on_95pct = sprite.ssim_above_lod_fraction >= 0.95,
          .mean_psnr_above_lod = sprite.mean_psnr > lod.mean_psnr,
          .mean_psnr_above_lod_on_sprite_frames =
              sprite.mean_psnr_sprite_frames > lod.mean_psnr_sprite_frames};
}

}  // namespace terrasprite::lodsprite
