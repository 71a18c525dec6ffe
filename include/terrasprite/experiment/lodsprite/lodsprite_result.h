// SPDX-License-Identifier: MIT
// What one LOD-sprite run (run_lodsprite) measured, as typed values: the
// per-frame rows, the per-renderer summaries, the sweeps, the cache pass and
// the same-frame figures. The report module writes it out (JSON, plots,
// index.html), so nothing is ever read back out of JSON.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/common/image.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/experiment/lodsprite/async_display.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/error_metric.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/terrain/terrain_info.h"

namespace terrasprite::lodsprite {

/// Where a sweep point's sprite figures come from.
enum class SweepMethod {
  kMainRun,       ///< the main run's, at the main setting
  kSeparatePass,  ///< a separate timed pass at the point's setting
};
/// "main run", "separate timed pass".
const char* to_string(SweepMethod m);

/// The paper's same-frame comparisons.
enum class SameFrameFigure {
  kFig13,  ///< checkerboard texture
  kFig14,  ///< the terrain's own texture
};
/// "fig13", "fig14": the JSON key and the stem of its PNG files.
const char* to_string(SameFrameFigure f);

/// "paper", "exact", "contrast".
const char* to_string(ErrorMetric m);
/// The unit of a metric's threshold: "px", or "grey levels" for kContrast.
const char* threshold_unit(ErrorMetric m);
/// "plain", "rich".
const char* to_string(TerrainShading s);

/// One displayed frame of the main run: the sprite renderer's frame and the
/// full-resolution and plain-LOD frames of the same camera. Times in ms.
struct LodspriteFrame {
  int frame = 0;
  FrameClass cls = FrameClass::kSprite;
  /// Full resolution drawn, timed and scored on this frame (every frame unless
  /// --reference-every); when false full_ms and the scores are NaN.
  bool reference = true;
  double ms = 0, gpu_ms = 0, full_ms = 0, lod_ms = 0;
  double error_px = 0, error_px_exact = 0;  ///< paper metric / exact reprojection, pixels
  int error_samples = 0;
  double fallback_fraction = 0, resample_scale = 1, resample_aniso = 1, decision_cpu_ms = 0;
  double drape_px = 0;             ///< SpriteError::drape_px: how far plain LOD is off, pixels
  std::optional<Trigger> trigger;  ///< what made this a keyframe; none for sprite frames
  bool cache_hit = false;          ///< a cached keyframe was reused (a sprite frame)
  int keyframe = 0;                ///< the frame whose keyframe is in use
  QualityScore sprite, lod;        ///< each against the full-resolution frame
  bool key() const { return cls == FrameClass::kKey; }
};

/// One sweep setting's sprite pass (the main run's, or a separate timed pass).
struct SweepPass {
  int keyframes = 0;
  double keyframe_fraction = 0;
  double speedup = 0;               ///< main run's full total / this pass's total
  double speedup_from_medians = 0;  ///< n x median full / (k x median key + (n-k) x median sprite)
  double total_ms = 0, key_median_ms = 0, sprite_median_ms = 0;
  double mean_ssim = 0;
  SweepMethod measured_in = SweepMethod::kSeparatePass;
};

struct ThresholdPoint {
  double threshold_px = 0;
  SweepPass pass;
};

struct LodQuadsPoint {
  int lod_quads = 0;
  SweepPass pass;
};

struct FrameCountPoint {
  int frames = 0, keyframes = 0;
  double keyframe_fraction = 0;
};

/// The keyframe cache against a separate timed pass without it (same path).
struct CacheSummary {
  std::size_t size_bytes = 0;
  CachePolicy policy = CachePolicy::kLeastRecentlyUsed;
  double accept = 0;
  int capacity_keyframes = 0;
  int keyframes = 0, keyframes_without_cache = 0, hits = 0;
  double saving = 0;  ///< 1 - keyframes / keyframes_without_cache
  double mean_ssim = 0, mean_ssim_without_cache = 0;
  double total_ms = 0, total_ms_without_cache = 0;
};

/// One keyframe trigger's separate scored pass (TriggerComparison).
struct TriggerSide {
  ErrorMetric metric = ErrorMetric::kPaper;
  double threshold = 0;  ///< in threshold_unit(metric)
  int keyframes = 0;
  double mean_ssim = 0, mean_psnr = 0, min_ssim = 0;
};

/// The run's keyframe trigger against the other kind (geometric against the
/// predicted image error, or back) at the same keyframe count: the other's
/// threshold found by bisection over keyframe-only simulations.
struct TriggerComparison {
  TriggerSide main, other;
  int simulations = 0;  ///< keyframe-only simulations the bisection ran
};

/// The paper's Figs. 13-14: one frame full / LOD / sprite, and the sprite's
/// and LOD's difference images against full resolution (|full - x| x 4).
struct FigureCompare {
  SameFrameFigure name = SameFrameFigure::kFig13;
  std::string texture;
  int frame = 0, keyframe = 0;
  QualityScore lod, sprite;
  Image full_image, lod_image, sprite_image, diff_lod_image, diff_sprite_image;
};

struct LodSummary {
  double total_ms = 0, median_ms = 0;
  /// mean_psnr_sprite_frames: NaN when no sprite frame was scored.
  double mean_psnr = 0, mean_psnr_sprite_frames = 0, mean_ssim = 0, min_ssim = 0, mean_flip = 0;
};

struct SpriteSummary {
  double total_ms = 0, median_ms = 0, p99_ms = 0;
  double decision_cpu_median_ms = 0, decision_cpu_p99_ms = 0;
  int keyframes = 0, sprite_frames = 0;
  double key_median_ms = 0, sprite_median_ms = 0;
  /// mean_psnr_sprite_frames: NaN when no sprite frame was scored.
  double mean_psnr = 0, mean_psnr_sprite_frames = 0, mean_ssim = 0, min_ssim = 0, mean_flip = 0;
  double ssim_above_lod_fraction = 0, ssim_above_lod_fraction_sprite_frames = 0;
};

/// Frames over 10x their class median: this shared machine's stalls.
struct StallCounts {
  int full = 0, lod = 0, key = 0, sprite = 0;
};

/// The speed-up bound 1 / (f + (1 - f) / r) of the measured f and r.
struct SpeedupBound {
  double f = 0;  ///< keyframe fraction
  /// median full / median sprite frame; r, the bound and the efficiency are
  /// NaN when the run has no sprite frame (nothing to divide by).
  double r = 0;
  double speedup_bound = 0, efficiency = 0, key_over_full_median = 0;
};

/// A target's outcome: met or missed only where its measurement means something.
enum class TargetState { kMet, kMissed, kNotApplicable };

struct TargetCheck {
  TargetState state = TargetState::kNotApplicable;
  std::string why;  ///< kNotApplicable: why this run cannot tell
  static TargetCheck of(bool met) { return {met ? TargetState::kMet : TargetState::kMissed, {}}; }
  static TargetCheck not_applicable(std::string why) {
    return {TargetState::kNotApplicable, std::move(why)};
  }
};

/// The paper's keyframe budget, speed-up and quality against plain LOD: the
/// JSON's `targets` and the report's target table, decided here once.
struct LodspriteTargets {
  TargetCheck keyframes_at_most_28;     ///< only for the paper's 460 frames along its path
  TargetCheck efficiency_at_least_0_9;  ///< needs keyframes and sprite frames
  TargetCheck ssim_above_lod_on_95pct;  ///< needs scored sprite frames
  TargetCheck mean_psnr_above_lod;      ///< needs scored sprite frames
  TargetCheck mean_psnr_above_lod_on_sprite_frames;  ///< needs scored sprite frames
};

/// The keyframes one trigger fired, and the values it fired at: the error
/// (the run's metric, against threshold_px) and the trigger's own measure
/// (kScale: the resample scale, kFallback: the fallback fraction, kError: the
/// error again; NaN for kFirst and kForced).
struct KeyframeTriggerRow {
  Trigger trigger = Trigger::kFirst;
  int keyframes = 0;
  double error_median = 0, error_max = 0;
  double measure_median = 0, measure_max = 0;
};

struct LodspriteResult {
  // ---- what ran ----
  std::string gl_renderer;
  TerrainInfo terrain;
  int width = 0, height = 0;
  int frames = 0;  ///< displayed frames (2 x the path's with there_and_back)
  std::string path;
  int lod_quads = 0;
  CoarseMesh mesh = CoarseMesh::kUniform;  ///< the sprite's coarse mesh
  long long mesh_triangles = 0;  ///< its triangle budget (uniform: 2 x lod_quads^2, plain LOD's)
  double threshold_px = 0;
  ErrorMetric metric = ErrorMetric::kPaper;
  double max_fallback_fraction = 0, sharp_px = 0;
  double key_margin = 0, key_supersample = 1;
  TerrainShading shading = TerrainShading::kPlain;
  double max_resample_scale = 0;   ///< may be +inf (the trigger off): JSON null
  bool anisotropic_scale = false;  ///< the scale trigger reads the worst axis
  double scale_per_drape_px = 0;   ///< SpriteOptions::scale_per_drape_px
  bool there_and_back = false;
  int sweep_score_every = 1;  ///< the one used: a multiple of reference_every
  /// Full resolution drawn (and the others scored) on every n-th frame;
  /// reference_frames of them. With n > 1 full_total_ms is their mean x frames
  /// and every quality figure is over those frames.
  int reference_every = 1, reference_frames = 0;
  std::string video;  ///< file name inside the output directory; empty: none
  // ---- what it measured ----
  double full_total_ms = 0, full_median_ms = 0;
  LodSummary lod;
  SpriteSummary sprite;
  double speedup = 0, speedup_from_medians = 0;
  StallCounts stalls;
  SpeedupBound bound;
  std::vector<ThresholdPoint> threshold_sweep;
  std::vector<FrameCountPoint> frame_count_sweep;
  std::vector<LodQuadsPoint> lod_sweep;
  std::optional<CacheSummary> cache;
  std::optional<TriggerComparison> trigger_comparison;  ///< --compare-trigger
  std::optional<AsyncComparison> async;                 ///< the simulated displays (--async)
  std::vector<FigureCompare> figures;
  std::vector<LodspriteFrame> per_frame;

  LodspriteTargets targets() const;
  /// The main run's keyframes by the trigger that fired them (cache reuses
  /// are sprite frames, not counted), triggers in enum order, empty ones left out.
  std::vector<KeyframeTriggerRow> keyframes_by_trigger() const;
  /// The per-frame error column the keyframe threshold is compared with.
  double trigger_error(const LodspriteFrame& f) const {
    return metric == ErrorMetric::kPaper ? f.error_px : f.error_px_exact;
  }
};

/// How the sweeps' speed-ups are measured: the JSON and the page both say it.
inline constexpr const char* kSweepSpeedupMethod =
    "speedup: measured, total frame time of the sprite pass (the main run, or a separate "
    "timed pass for other settings, scored after the pass) against the main run's "
    "full-resolution total; speedup_from_medians: derived, n x median full / (k x median "
    "key + (n - k) x median sprite) with that pass's medians";

}  // namespace terrasprite::lodsprite
