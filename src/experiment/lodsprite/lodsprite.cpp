// SPDX-License-Identifier: MIT
// The measured run behind `bench lodsprite` and `demo`: full resolution, plain
// LOD and LOD-sprite interleaved frame by frame on one path (so machine noise
// hits all three alike), each frame scored against the full-resolution frame
// after the timed spans; then the paper's sweeps (its Figs. 10-12) and the
// same-frame comparison images (its Figs. 13-14).
#include "terrasprite/experiment/lodsprite/lodsprite.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "experiment/lodsprite/frame_class.h"
#include "experiment/lodsprite/sprite_pass.h"
#include "experiment/lodsprite/stages.h"
#include "experiment/lodsprite/trigger_comparison.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite::lodsprite {
namespace {

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

void validate(const LodspriteOptions& c) {
  if (c.frames < 1 || c.frames > 1000000)
    throw InputError(fmt::format("--frames {}: must be between 1 and 1000000", c.frames));
  if (c.lod_quads < 1)
    throw InputError(fmt::format("--lod-quads {}: must be at least 1", c.lod_quads));
  if (!(c.threshold_px > 0))
    throw InputError(fmt::format("--threshold {}: must be positive", c.threshold_px));
  for (double t : c.thresholds)
    if (!(t > 0))
      throw InputError(fmt::format("--thresholds: {} is not a positive number of pixels", t));
  for (int n : c.frame_counts)
    if (n < 1 || n > 100000)
      throw InputError(fmt::format("--frame-counts: {} must be between 1 and 100000", n));
  for (int q : c.lod_sweep)
    if (q < 1) throw InputError(fmt::format("--lod-sweep: {} quads must be at least 1", q));
  if (c.cache_bytes > 0 && c.cache_bytes < std::size_t(2) * c.width * c.height * 8)
    throw InputError(
        fmt::format("--cache-mb {:.3g}: must hold at least two {}x{} keyframes ({:.3g} MB)",
                    double(c.cache_bytes) / (1 << 20), c.width, c.height,
                    2.0 * c.width * c.height * 8 / (1 << 20)));
  if (!(c.cache_accept > 0 && c.cache_accept <= 1))
    throw InputError(fmt::format("--cache-accept {}: must be in (0, 1]", c.cache_accept));
  if (!(c.display_hz >= 0) || c.display_hz > 1000)
    throw InputError(fmt::format("--display-hz {}: must be 0 (flat out) to 1000", c.display_hz));
  if (!(c.async_lead > 0 && c.async_lead <= 1))
    throw InputError(fmt::format("--async-lead {}: must be in (0, 1]", c.async_lead));
  if (c.async && c.cache_bytes > 0)
    throw InputError("--async with --cache: the keyframe cache is not used with async keyframes");
  if (c.compare_trigger && c.cache_bytes > 0)
    throw InputError("--compare-trigger with --cache: cache reuses are not keyframe decisions");
  if (c.sweep_score_every < 1)
    throw InputError(
        fmt::format("--sweep-score-every {}: must be at least 1", c.sweep_score_every));
  if (c.reference_every < 1 || c.reference_every > 1000000)
    throw InputError(
        fmt::format("--reference-every {}: must be between 1 and 1000000", c.reference_every));
}

SpriteOptions sprite_options(const LodspriteOptions& c) {
  SpriteOptions so;
  so.lod_quads = c.lod_quads;
  so.mesh = c.mesh;
  so.mesh_triangles = c.mesh_triangles;
  so.threshold_px = c.threshold_px;
  so.async_lead = c.async_lead;
  so.metric = c.metric;
  so.max_fallback_fraction = c.max_fallback_fraction;
  so.max_resample_scale = c.max_resample_scale;
  so.anisotropic_scale = c.anisotropic_scale;
  so.scale_per_drape_px = c.scale_per_drape_px;
  so.sharp_px = c.sharp_px;
  so.key_margin = c.key_margin;
  so.key_supersample = c.key_supersample;
  so.cache_bytes = c.cache_bytes;
  so.cache_policy = c.cache_policy;
  so.cache_accept = c.cache_accept;
  return so;
}

// The sprite renderer's own figures for one main-run frame, recorded right
// after its draw (outside the timed span).
struct SpriteRecord {
  FrameClass cls = FrameClass::kSprite;
  SpriteError error;
  double decision_ms = 0;
  std::optional<Trigger> trigger;
  bool cache_hit = false;
};

struct MainRun {
  ExperimentResult run;              // runs "full" (reference frames only), "lod", "sprite"
  std::vector<SpriteRecord> sprite;  // one per displayed frame
  std::vector<Image> refs;           // full-resolution frames i with i % every == 0
};

// Full resolution (the reference, on every reference_every-th frame), plain
// LOD and LOD-sprite drawn interleaved, timed, then scored.
MainRun run_main(const LodspriteOptions& c, MeshRenderer& full, MeshRenderer& lod,
                 SpriteRenderer& sprite, const std::vector<Camera>& path, int every) {
  MainRun m;
  Experiment experiment;
  experiment.set_reference(full, "full");
  experiment.add({.renderer = &lod, .name = "lod", .score = true});
  experiment.add({.renderer = &sprite,
                  .name = "sprite",
                  .score = true,
                  .after_warmup = [&] { sprite.reset(); },
                  .annotate =
                      [&](const Frame&, FrameResult&) {
                        m.sprite.push_back({.cls = last_frame_class(sprite),
                                            .error = sprite.last_error(),
                                            .decision_ms = sprite.last_decision_ms(),
                                            .trigger = sprite.last_trigger(),
                                            .cache_hit = sprite.last_cache_hit()});
                      }});
  ExperimentOptions eo;
  eo.warmup_draws = 2;  // the sprite's first draw is a keyframe, its second a sprite frame
  eo.scorer = default_scorer(c.flip);
  eo.score_every = c.reference_every;  // the reference (and scoring) on every n-th frame
  eo.on_frame = [&](int i, const std::string& name, const Frame& f) {
    if (name == "full" && i % every == 0) m.refs.push_back(f.color);
    if (name == "sprite" && c.on_sprite_frame) c.on_sprite_frame(i, f);
  };
  if (c.progress) eo.progress = [&](int done, int total) { c.progress("main", done, total); };
  PathSource cameras(path);
  m.run = experiment.run(cameras, eo);
  return m;
}

// What ran: the settings and the machine, copied into the result.
void describe_run(const LodspriteOptions& c, const Terrain& terrain, const std::string& gl,
                  const SpriteRenderer& sprite, int n, int every, LodspriteResult& r) {
  r.gl_renderer = gl;
  r.terrain = terrain_info(terrain);
  r.width = c.width;
  r.height = c.height;
  r.frames = n;
  r.path = c.path;
  r.lod_quads = c.lod_quads;
  r.mesh = c.mesh;
  r.mesh_triangles =
      sprite.mesh_budget() > 0 ? sprite.mesh_budget() : 2LL * c.lod_quads * c.lod_quads;
  r.threshold_px = c.threshold_px;
  r.metric = c.metric;
  r.max_fallback_fraction = c.max_fallback_fraction;
  r.sharp_px = c.sharp_px;
  r.key_margin = c.key_margin;
  r.key_supersample = c.key_supersample;
  r.shading = c.shading;
  r.max_resample_scale = c.max_resample_scale;
  r.anisotropic_scale = c.anisotropic_scale;
  r.scale_per_drape_px = c.scale_per_drape_px;
  r.there_and_back = c.there_and_back;
  r.sweep_score_every = every;
  r.reference_every = c.reference_every;
  r.video = c.video;
}

// One displayed frame's row: `full` is null on frames without a reference.
LodspriteFrame frame_row(int i, const FrameResult& lod, const FrameResult& sprite,
                         const SpriteRecord& rec, const FrameResult* full) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const SpriteError& e = rec.error;
  LodspriteFrame row{.frame = i,
                     .cls = rec.cls,
                     .reference = full != nullptr,
                     .ms = sprite.ms,
                     .gpu_ms = sprite.gpu_ms,
                     .full_ms = full ? full->ms : nan,
                     .lod_ms = lod.ms,
                     .error_px = e.paper_px,
                     .error_px_exact = e.exact_px,
                     .error_samples = int(double(e.samples)),
                     .fallback_fraction = e.fallback_fraction(),
                     .resample_scale = e.resample_scale,
                     .resample_aniso = e.resample_aniso,
                     .decision_cpu_ms = rec.decision_ms,
                     .drape_px = e.drape_px,
                     .trigger = rec.trigger,
                     .cache_hit = rec.cache_hit};
  if (full) {
    row.lod = *lod.quality;
    row.sprite = *sprite.quality;
  } else {
    row.lod = row.sprite = {.psnr = nan, .ssim = nan, .flip = nan};
  }
  return row;
}

// The per-frame series the summaries are taken over.
struct FrameSeries {
  std::vector<double> full_ms, lod_ms, sprite_ms, key_ms, spr_ms, decision_ms;
  std::vector<double> lod_psnr, lod_ssim, lod_flip, sp_psnr, sp_ssim, sp_flip;
  std::vector<double> sp_psnr_sprite_only, lod_psnr_sprite_only;
  int keyframes = 0, ssim_above = 0, ssim_above_sprite_frames = 0, scored_sprite_frames = 0;
};

void add_to_series(const LodspriteFrame& row, FrameSeries& s) {
  s.sprite_ms.push_back(row.ms);
  s.lod_ms.push_back(row.lod_ms);
  s.decision_ms.push_back(row.decision_cpu_ms);
  (row.key() ? s.key_ms : s.spr_ms).push_back(row.ms);
  s.keyframes += row.key();
  if (!row.reference) return;
  const QualityScore &ls = row.lod, &ss = row.sprite;
  s.full_ms.push_back(row.full_ms);
  s.lod_psnr.push_back(ls.psnr);
  s.lod_ssim.push_back(ls.ssim);
  s.lod_flip.push_back(ls.flip);
  s.sp_psnr.push_back(ss.psnr);
  s.sp_ssim.push_back(ss.ssim);
  s.sp_flip.push_back(ss.flip);
  if (!row.key()) {
    s.sp_psnr_sprite_only.push_back(ss.psnr);
    s.lod_psnr_sprite_only.push_back(ls.psnr);
    ++s.scored_sprite_frames;
  }
  s.ssim_above += ss.ssim > ls.ssim;
  s.ssim_above_sprite_frames += !row.key() && ss.ssim > ls.ssim;
}

// The per-frame rows (into r.per_frame) and the series of their figures.
FrameSeries collect_frames(const MainRun& m, int n, LodspriteResult& r) {
  const RendererRun &full = m.run.run("full"), &lod = m.run.run("lod"),
                    &sprite = m.run.run("sprite");
  FrameSeries s;
  std::size_t next_ref = 0;
  int current_key = 0;
  for (int i = 0; i < n; ++i) {
    const bool has_ref = next_ref < full.frames.size() && full.frames[next_ref].frame == i;
    const FrameResult* ref = has_ref ? &full.frames[next_ref++] : nullptr;
    LodspriteFrame row = frame_row(i, lod.frames[i], sprite.frames[i], m.sprite[i], ref);
    if (row.key()) current_key = i;
    row.keyframe = current_key;
    add_to_series(row, s);
    r.per_frame.push_back(std::move(row));
  }
  return s;
}

double min_of(const std::vector<double>& v) {
  return *std::min_element(v.begin(), v.end());
}

// The mean, or NaN for no values (a figure with nothing to average is not 0).
double mean_or_nan(const std::vector<double>& v) {
  return v.empty() ? NAN : mean(v);
}

// Frames over 10x their class median: this shared machine's stalls weigh
// heavily in totals; counted so a reader can tell noise from cost.
int stalls(const std::vector<double>& v) {
  const double m = median(v);
  return int(std::count_if(v.begin(), v.end(), [&](double x) { return x > 10 * m; }));
}

// Totals, medians and mean scores of each renderer; the speed-up and its bound.
void summarize_series(const FrameSeries& s, int n, LodspriteResult& r) {
  const int scored = int(s.full_ms.size());
  r.reference_frames = scored;
  // Every frame's reference drawn: the measured total; else the sampled
  // frames' mean x n (an estimate, the JSON says which).
  r.full_total_ms = scored == n ? sum(s.full_ms) : mean(s.full_ms) * n;
  r.full_median_ms = median(s.full_ms);
  r.lod = {.total_ms = sum(s.lod_ms),
           .median_ms = median(s.lod_ms),
           .mean_psnr = mean(s.lod_psnr),
           .mean_psnr_sprite_frames = mean_or_nan(s.lod_psnr_sprite_only),
           .mean_ssim = mean(s.lod_ssim),
           .min_ssim = min_of(s.lod_ssim),
           .mean_flip = mean(s.lod_flip)};
  r.sprite = {.total_ms = sum(s.sprite_ms),
              .median_ms = median(s.sprite_ms),
              .p99_ms = percentile(s.sprite_ms, 99),
              .decision_cpu_median_ms = median(s.decision_ms),
              .decision_cpu_p99_ms = percentile(s.decision_ms, 99),
              .keyframes = s.keyframes,
              .sprite_frames = n - s.keyframes,
              .key_median_ms = median(s.key_ms),
              .sprite_median_ms = median(s.spr_ms),
              .mean_psnr = mean(s.sp_psnr),
              .mean_psnr_sprite_frames = mean_or_nan(s.sp_psnr_sprite_only),
              .mean_ssim = mean(s.sp_ssim),
              .min_ssim = min_of(s.sp_ssim),
              .mean_flip = mean(s.sp_flip),
              .ssim_above_lod_fraction = double(s.ssim_above) / scored,
              .ssim_above_lod_fraction_sprite_frames =
                  s.scored_sprite_frames > 0
                      ? double(s.ssim_above_sprite_frames) / s.scored_sprite_frames
                      : 1.0};
  r.stalls = {stalls(s.full_ms), stalls(s.lod_ms), stalls(s.key_ms), stalls(s.spr_ms)};
}

void speedup_and_bound(LodspriteResult& r) {
  const int n = r.frames, keys = r.sprite.keyframes;
  const double full_median = r.full_median_ms, spr_median = r.sprite.sprite_median_ms;
  r.speedup = r.full_total_ms / std::max(r.sprite.total_ms, 1e-9);
  r.speedup_from_medians = median_speedup(n, keys, full_median, r.sprite.key_median_ms, spr_median);
  SpeedupBound& b = r.bound;
  b.f = double(keys) / n;
  // No sprite frame: no sprite median to divide by, so no r and no bound.
  b.r = r.sprite.sprite_frames > 0 ? full_median / std::max(spr_median, 1e-9) : NAN;
  b.speedup_bound = 1.0 / (b.f + (1.0 - b.f) / b.r);
  b.efficiency = r.speedup / b.speedup_bound;
  b.key_over_full_median = r.sprite.key_median_ms / std::max(full_median, 1e-9);
}

// The display simulated with asynchronous keyframes, beside a synchronous one.
AsyncComparison compare_async(const StageContext& s, const GlContext& gl,
                              const LodspriteResult& r) {
  AsyncComparison ac = run_async_display(gl, s.scene, s.path, s.width, s.height, s.sprite, s.refs,
                                         s.every, s.options.display_hz);
  ac.main_run_mean_ssim = mean_every(r, s.every, &QualityScore::ssim);
  ac.main_run_mean_psnr = mean_every(r, s.every, &QualityScore::psnr);
  std::vector<double> sprite_ssim;
  for (int i = 0; i < r.frames; i += s.every)
    if (!r.per_frame[i].key()) sprite_ssim.push_back(r.per_frame[i].sprite.ssim);
  ac.main_run_mean_ssim_sprite_frames = mean(sprite_ssim);
  return ac;
}
}  // namespace

ErrorMetric parse_metric(const std::string& text) {
  if (text == "paper") return ErrorMetric::kPaper;
  if (text == "exact") return ErrorMetric::kExact;
  if (text == "contrast") return ErrorMetric::kContrast;
  throw InputError(fmt::format("--metric {}: must be 'paper', 'exact' or 'contrast'", text));
}

TerrainShading parse_shading(const std::string& text) {
  if (text == "plain") return TerrainShading::kPlain;
  if (text == "rich") return TerrainShading::kRich;
  throw InputError(fmt::format("--shading {}: must be 'plain' or 'rich'", text));
}

CachePolicy parse_cache_policy(const std::string& text) {
  if (text == "lru") return CachePolicy::kLeastRecentlyUsed;
  if (text == "farthest") return CachePolicy::kFarthest;
  throw InputError(fmt::format("--cache-policy {}: must be 'lru' or 'farthest'", text));
}

LodspriteResult run_lodsprite(const LodspriteOptions& c, const Terrain& terrain) {
  validate(c);
  const int w = c.width, h = c.height;
  // Sweeps score only on frames that have a full-resolution reference.
  const int every = std::lcm(c.sweep_score_every, c.reference_every);
  std::vector<Camera> path = make_path(c.path, terrain.heights, c.frames, double(w) / h);
  if (c.there_and_back) path.insert(path.end(), path.rbegin(), path.rend());
  const int n = int(path.size());

  GlContext gl;
  Scene scene(terrain);
  scene.set_shading(c.shading);
  MeshRenderer full(scene, w, h, 0), lod(scene, w, h, c.lod_quads);
  const SpriteOptions so = sprite_options(c);
  SpriteRenderer sprite(scene, w, h, so);
  const MainRun main_run = run_main(c, full, lod, sprite, path, every);

  LodspriteResult r;
  describe_run(c, terrain, gl.renderer(), sprite, n, every, r);
  summarize_series(collect_frames(main_run, n, r), n, r);
  speedup_and_bound(r);

  const StageContext stages{.options = c,
                            .terrain = terrain,
                            .scene = scene,
                            .path = path,
                            .sprite = so,
                            .refs = main_run.refs,
                            .width = w,
                            .height = h,
                            .every = every};
  if (c.async) r.async = compare_async(stages, gl, r);
  run_sweeps(stages, r);
  if (c.cache_bytes > 0) r.cache = compare_cache(stages, r);
  if (c.compare_trigger)
    r.trigger_comparison = compare_triggers(scene, path, w, h, so, main_run.refs, every);
  r.figures = same_frame_figures(stages, r);
  return r;
}

}  // namespace terrasprite::lodsprite
