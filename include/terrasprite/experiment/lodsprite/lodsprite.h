// SPDX-License-Identifier: MIT
// The LOD-sprite paper reproduction (Chen et al. 1999): full resolution, plain
// LOD and LOD-sprite timed on one path, scored against the full-resolution
// reference, plus the sweeps and figures of the paper's section 4.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "terrasprite/camera/frame.h"
#include "terrasprite/experiment/lodsprite/lodsprite_result.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/error_metric.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite::lodsprite {

/// What run_lodsprite() runs. Sizes in pixels, thresholds in the metric's
/// unit (threshold_unit()). Out-of-range values: InputError naming the
/// option that sets it (validated by run_lodsprite()).
struct LodspriteOptions {
  std::string path = "paper";
  int frames = 460;
  int width = 512, height = 512;
  int lod_quads = 16;
  CoarseMesh mesh = CoarseMesh::kUniform;  ///< SpriteOptions::mesh
  long long mesh_triangles = 0;            ///< SpriteOptions::mesh_triangles
  double threshold_px = 1.0;
  ErrorMetric metric = ErrorMetric::kPaper;
  double max_fallback_fraction = 1.0;
  double max_resample_scale = 1.25;
  bool anisotropic_scale = false;  ///< SpriteOptions::anisotropic_scale
  double scale_per_drape_px = SpriteOptions{}.scale_per_drape_px;
  double sharp_px = 0.5;
  double key_margin = 0, key_supersample = 1;  ///< SpriteOptions::key_margin, key_supersample
  /// The sweeps (paper Figs. 10-12): keyframe thresholds, frame counts along
  /// the same path, coarse quads per side. An empty list skips that sweep.
  std::vector<double> thresholds = {0.25, 0.5, 1, 2, 4, 8};
  std::vector<int> frame_counts = {115, 230, 460, 920, 1840};
  std::vector<int> lod_sweep = {8, 16, 32, 64};
  /// The path flown there and back: its `frames` cameras, then the same
  /// cameras in reverse order (2 x frames in all).
  bool there_and_back = false;
  /// Keyframe cache budget in bytes (0 = off) and eviction policy; with the
  /// cache on, a separate timed pass without it gives keyframes_without_cache.
  std::size_t cache_bytes = 0;
  CachePolicy cache_policy = CachePolicy::kLeastRecentlyUsed;
  double cache_accept = 0.5;
  /// Also fly the path as two simulated displays, synchronous and with
  /// asynchronous keyframes (JSON `async_run`); not with the cache.
  bool async = false;
  /// The simulated displays' refresh rate (frames presented on its slots, so
  /// the keyframe worker gets the CPU between frames); 0 = flat out.
  double display_hz = 60;
  double async_lead = 0.6;    ///< SpriteOptions::async_lead
  int sweep_score_every = 1;  ///< sweeps score SSIM on every n-th frame
  /// The main run draws, times and scores the full-resolution reference (and
  /// scores plain LOD and the sprite) on every n-th frame only, from frame 0;
  /// the full-resolution total is then their mean x frames. Sprite and LOD
  /// frames are all drawn and timed. 1 = every frame. Sweeps score on frames
  /// that have a reference: every lcm(sweep_score_every, reference_every)-th.
  int reference_every = 1;
  /// Also compare the keyframe trigger with the other kind at the same
  /// keyframe count (compare_triggers(); JSON `trigger_comparison`); not with the cache.
  bool compare_trigger = false;
  /// Terrain shading of every renderer (full, LOD, keyframes and drape quads).
  TerrainShading shading = TerrainShading::kPlain;
  bool flip = true;  ///< FLIP per frame in the main run
  /// Called with (frame, sprite frame) after scoring, e.g. to save it.
  std::function<void(int, const Frame&)> on_sprite_frame;
  /// A video of the sprite frames beside the report (file name inside the
  /// report's directory), embedded next to the figures; empty: none. The
  /// caller writes it (e.g. from on_sprite_frame).
  std::string video;
  /// Progress of a stage ("main", "sweeps"): `done` of `total` steps.
  std::function<void(const char* stage, int done, int total)> progress;
};

/// Flies full resolution, plain LOD and LOD-sprite interleaved along the
/// path (GL context of its own), scores each frame against full resolution
/// after its timed spans, then runs the sweeps, the optional cache, trigger
/// and async comparisons and the same-frame figures; returns what it
/// measured (report/lodsprite_report.h writes it out). Bad settings:
/// InputError; no GL device: DeviceError.
LodspriteResult run_lodsprite(const LodspriteOptions& options, const Terrain& terrain);

/// "paper" | "exact" | "contrast" -> metric; throws InputError naming --metric.
ErrorMetric parse_metric(const std::string& text);
/// "plain" | "rich" -> shading; throws InputError naming --shading.
TerrainShading parse_shading(const std::string& text);
/// "lru" | "farthest" -> policy; throws InputError naming --cache-policy.
CachePolicy parse_cache_policy(const std::string& text);

}  // namespace terrasprite::lodsprite
