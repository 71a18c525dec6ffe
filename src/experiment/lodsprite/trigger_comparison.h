// SPDX-License-Identifier: MIT
// `bench lodsprite --compare-trigger`: the paper's geometric keyframe trigger
// against one on predicted image error (ErrorMetric::kContrast), compared at
// an equal number of keyframes, which is what either trigger spends.
#pragma once
#include <span>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/common/image.h"
#include "terrasprite/experiment/lodsprite/lodsprite_result.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite::lodsprite {

/// The error triggers alone (the scale and fallback triggers off on both
/// sides, so neither spends keyframes the metrics did not ask for):
/// keyframes `main`'s metric spends on `path`; the other kind of metric (contrast for
/// paper or exact, paper for contrast) at the threshold giving the same
/// count (log-scale bisection, at most 24 keyframe-only simulations; the
/// nearest count when none is equal, ties to fewer keyframes); then both
/// flown as timed passes scored every `every`-th frame against `refs`.
/// Not with the keyframe cache (its reuses are not keyframe decisions).
TriggerComparison compare_triggers(Scene& scene, std::span<const Camera> path, int width,
                                   int height, const SpriteOptions& main,
                                   const std::vector<Image>& refs, int every);

}  // namespace terrasprite::lodsprite
