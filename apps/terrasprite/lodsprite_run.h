// SPDX-License-Identifier: MIT
// The LOD-sprite paper reproduction (Chen et al. 1999): full resolution, plain
// LOD and LOD-sprite timed on one path, scored against the full-resolution
// reference, plus the sweeps and figures of the paper's section 4.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "lodsprite_result.h"
#include "terrasprite/camera/frame.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/error_metric.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite::cli {

struct LodspriteConfig {
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
  /// A video of the sprite frames beside the report (file name inside `out`),
  /// embedded next to the figures; empty: none.
  std::string video;
};

/// Runs everything and writes the figure PNGs (Figs. 13-14) into `out`;
/// returns what it measured (to_json() and write_lodsprite_report() write it
/// out). `label` prefixes the progress bar. Bad settings: InputError.
LodspriteResult run_lodsprite(const LodspriteConfig& config, const Terrain& terrain, OutputDir& out,
                              const std::string& label);

/// "paper" | "exact" -> metric; throws InputError naming --metric.
ErrorMetric parse_metric(const std::string& text);
const char* metric_name(ErrorMetric m);
/// "lru" | "farthest" -> policy; throws InputError naming --cache-policy.
CachePolicy parse_cache_policy(const std::string& text);

}  // namespace terrasprite::cli
