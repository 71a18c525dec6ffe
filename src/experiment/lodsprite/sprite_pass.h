// SPDX-License-Identifier: MIT
// Separate LOD-sprite passes of run_lodsprite(), beside its interleaved
// main run: a timed, scored pass at other settings (the sweeps, the cache
// comparison, the trigger comparison) and a keyframe-count simulation.
#pragma once
#include <span>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/common/image.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite::lodsprite {

struct PassResult {
  int keyframes = 0;
  double total_ms = 0;
  double key_median_ms = 0, sprite_median_ms = 0;
  double mean_ssim = 0;
  double mean_psnr = 0;  ///< RGB PSNR in dB, identical frames counted at 100
  double min_ssim = 0;
  int cache_hits = 0;
};

/// One timed LOD-sprite pass over `path` through the experiment driver; every
/// `every`-th frame is kept and scored against refs[i / every] after the whole
/// pass, so scoring threads never overlap a timed frame. A current context.
PassResult sprite_pass(Scene& scene, std::span<const Camera> path, int width, int height,
                       const SpriteOptions& options, const std::vector<Image>& refs, int every);

/// Keyframe count only: the triggers decide on every frame, keyframes are
/// rendered (their depth, and colour for the contrast metric, feed the
/// metric), sprite frames are not drawn.
int simulate_keyframes(Scene& scene, std::span<const Camera> path, int width, int height,
                       const SpriteOptions& options);

}  // namespace terrasprite::lodsprite
