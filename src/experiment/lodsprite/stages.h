// SPDX-License-Identifier: MIT
// The stages of run_lodsprite() after its interleaved main run: the paper's
// sweeps, the keyframe-cache comparison and the same-frame figures. Each
// reads the main run's result and adds its own part.
#pragma once
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/common/image.h"
#include "terrasprite/experiment/lodsprite/lodsprite.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite::lodsprite {

/// What the stages share; all owned by run_lodsprite(), which keeps the GL
/// context current while they run.
struct StageContext {
  const LodspriteOptions& options;
  const Terrain& terrain;
  Scene& scene;
  const std::vector<Camera>& path;  ///< the displayed frames' cameras
  const SpriteOptions& sprite;      ///< the main run's sprite settings
  /// Full-resolution frames i with i % every == 0 (every: the sweeps' scoring step).
  const std::vector<Image>& refs;
  int width = 0, height = 0, every = 1;
};

/// Speed-up from per-class medians, robust to the machine's stalls: n full
/// frames against k keyframes and n - k sprite frames (0 when nothing costs).
double median_speedup(int n, int keys, double full_median, double key_median, double sprite_median);

/// The sprite's mean of `figure` over the frames the sweeps score (every
/// `every`-th frame of the main run).
double mean_every(const LodspriteResult& r, int every, double QualityScore::*figure);

/// The threshold, frame-count and coarse-mesh sweeps (paper Figs. 10-12):
/// the main run's figures at the main setting, separate passes elsewhere.
void run_sweeps(const StageContext& s, LodspriteResult& r);

/// The same path with the keyframe cache off, against the main run's cache.
CacheSummary compare_cache(const StageContext& s, const LodspriteResult& r);

/// The paper's Figs. 13 and 14: the sprite frame with the largest exact
/// error, drawn full / LOD / sprite on a checker texture and the terrain's own.
std::vector<FigureCompare> same_frame_figures(const StageContext& s, const LodspriteResult& r);

}  // namespace terrasprite::lodsprite
