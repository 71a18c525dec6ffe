// SPDX-License-Identifier: MIT
// The measured run behind `bench lodsprite` and `demo`: full resolution, plain
// LOD and LOD-sprite interleaved frame by frame on one path (so machine noise
// hits all three alike), each frame scored against the full-resolution frame
// after the timed spans; then the paper's sweeps (its Figs. 10-12) and the
// same-frame comparison images (its Figs. 13-14).
#include "lodsprite_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "cli_common.h"
#include "lodsprite_passes.h"
#include "lodsprite_trigger.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/terrain/texture_gen.h"

namespace terrasprite::cli {
namespace {

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

// Speed-up from per-class medians, robust to the machine's stalls:
// n full frames against k keyframes and n - k sprite frames.
double median_speedup(int n, int keys, double full_median, double key_median,
                      double sprite_median) {
  const double cost = keys * key_median + (n - keys) * sprite_median;
  return cost > 0 ? n * full_median / cost : 0.0;
}

void validate(const LodspriteConfig& c) {
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

}  // namespace

ErrorMetric parse_metric(const std::string& text) {
  if (text == "paper") return ErrorMetric::kPaper;
  if (text == "exact") return ErrorMetric::kExact;
  if (text == "contrast") return ErrorMetric::kContrast;
  throw InputError(fmt::format("--metric {}: must be 'paper', 'exact' or 'contrast'", text));
}

const char* metric_name(ErrorMetric m) {
  return m == ErrorMetric::kPaper ? "paper" : m == ErrorMetric::kExact ? "exact" : "contrast";
}

CachePolicy parse_cache_policy(const std::string& text) {
  if (text == "lru") return CachePolicy::kLeastRecentlyUsed;
  if (text == "farthest") return CachePolicy::kFarthest;
  throw InputError(fmt::format("--cache-policy {}: must be 'lru' or 'farthest'", text));
}

LodspriteResult run_lodsprite(const LodspriteConfig& cfg, const Terrain& terrain, OutputDir& out,
                              const std::string& label) {
  validate(cfg);
  const int w = cfg.width, h = cfg.height, ref_every = cfg.reference_every;
  // Sweeps score only on frames that have a full-resolution reference.
  const int every = std::lcm(cfg.sweep_score_every, ref_every);
  const double aspect = double(w) / h;
  std::vector<Camera> path = make_path(cfg.path, terrain.heights, cfg.frames, aspect);
  if (cfg.there_and_back) path.insert(path.end(), path.rbegin(), path.rend());
  const int n = int(path.size());

  GlContext gl;
  Scene scene(terrain);
  scene.set_shading(cfg.shading);
  MeshRenderer full(scene, w, h, 0), lod(scene, w, h, cfg.lod_quads);
  SpriteOptions so;
  so.lod_quads = cfg.lod_quads;
  so.mesh = cfg.mesh;
  so.mesh_triangles = cfg.mesh_triangles;
  so.threshold_px = cfg.threshold_px;
  so.async_lead = cfg.async_lead;
  so.metric = cfg.metric;
  so.max_fallback_fraction = cfg.max_fallback_fraction;
  so.max_resample_scale = cfg.max_resample_scale;
  so.anisotropic_scale = cfg.anisotropic_scale;
  so.scale_per_drape_px = cfg.scale_per_drape_px;
  so.sharp_px = cfg.sharp_px;
  so.key_margin = cfg.key_margin;
  so.key_supersample = cfg.key_supersample;
  so.cache_bytes = cfg.cache_bytes;
  so.cache_policy = cfg.cache_policy;
  so.cache_accept = cfg.cache_accept;
  SpriteRenderer sprite(scene, w, h, so);
  // ---- main run: interleaved, timed, then scored outside the timed spans ----
  Experiment experiment;
  experiment.set_reference(full, "full");
  experiment.add({.renderer = &lod, .name = "lod", .score = true});
  experiment.add({.renderer = &sprite,
                  .name = "sprite",
                  .score = true,
                  .after_warmup = [&] { sprite.reset(); },
                  .annotate =
                      [&](const Frame&, FrameResult& r) {
                        const SpriteError& e = sprite.last_error();
                        r.counters = {{"error_px", e.paper_px},
                                      {"error_px_exact", e.exact_px},
                                      {"error_samples", double(e.samples)},
                                      {"fallback_fraction", e.fallback_fraction()},
                                      {"resample_scale", e.resample_scale},
                                      {"resample_aniso", e.resample_aniso},
                                      {"drape_px", e.drape_px},
                                      {"decision_cpu_ms", sprite.last_decision_ms()}};
                        if (sprite.last_trigger())
                          r.tags["trigger"] = to_string(*sprite.last_trigger());
                        if (sprite.last_cache_hit()) r.tags["trigger"] = "cache";
                      }});
  std::vector<Image> refs;
  ExperimentOptions eo;
  eo.warmup_draws = 2;  // the sprite's first draw is a keyframe, its second a sprite frame
  eo.scorer = default_scorer(cfg.flip);
  eo.score_every = ref_every;  // the reference (and scoring) on every ref_every-th frame
  eo.on_frame = [&](int i, const std::string& name, const Frame& f) {
    if (name == "full" && i % every == 0) refs.push_back(f.color);
    if (name == "sprite" && cfg.on_sprite_frame) cfg.on_sprite_frame(i, f);
  };
  Progress progress(label + " main");
  eo.progress = std::ref(progress);
  PathSource cameras(path);
  const ExperimentResult run = experiment.run(cameras, eo);
  const RendererRun &full_run = run.run("full"), &lod_run = run.run("lod"),
                    &sprite_run = run.run("sprite");

  LodspriteResult res;
  res.gl_renderer = gl.renderer();
  res.terrain = terrain_info(terrain);
  res.width = w;
  res.height = h;
  res.frames = n;
  res.path = cfg.path;
  res.lod_quads = cfg.lod_quads;
  res.mesh = to_string(cfg.mesh);
  res.mesh_triangles =
      sprite.mesh_budget() > 0 ? sprite.mesh_budget() : 2LL * cfg.lod_quads * cfg.lod_quads;
  res.threshold_px = cfg.threshold_px;
  res.metric = metric_name(cfg.metric);
  res.max_fallback_fraction = cfg.max_fallback_fraction;
  res.sharp_px = cfg.sharp_px;
  res.key_margin = cfg.key_margin;
  res.key_supersample = cfg.key_supersample;
  res.shading = cfg.shading == TerrainShading::kRich ? "rich" : "plain";
  res.max_resample_scale = cfg.max_resample_scale;
  res.anisotropic_scale = cfg.anisotropic_scale;
  res.scale_per_drape_px = cfg.scale_per_drape_px;
  res.there_and_back = cfg.there_and_back;
  res.sweep_score_every = every;
  res.reference_every = ref_every;
  res.video = cfg.video;

  // The reference's figures (full_ms, scores) only on reference frames; the
  // per-frame rows carry NaN on the others.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> full_ms, lod_ms(n), sprite_ms(n), key_ms, spr_ms, decision_ms;
  std::vector<double> lod_psnr, lod_ssim, lod_flip, sp_psnr, sp_ssim, sp_flip, sp_psnr_sprite_only,
      lod_psnr_sprite_only;
  int keyframes = 0, current_key = 0, ssim_above = 0, ssim_above_sprite_frames = 0,
      scored_sprite_frames = 0;
  std::size_t next_ref = 0;
  for (int i = 0; i < n; ++i) {
    const FrameResult &b = lod_run.frames[i], &c = sprite_run.frames[i];
    const bool has_ref = next_ref < full_run.frames.size() && full_run.frames[next_ref].frame == i;
    const FrameResult* a = has_ref ? &full_run.frames[next_ref++] : nullptr;
    LodspriteFrame row;
    row.frame = i;
    row.key = c.cls == "key";
    row.reference = has_ref;
    row.ms = sprite_ms[i] = c.ms;
    row.gpu_ms = c.gpu_ms;
    row.full_ms = a ? a->ms : nan;
    row.lod_ms = lod_ms[i] = b.ms;
    row.error_px = c.counters.at("error_px");
    row.error_px_exact = c.counters.at("error_px_exact");
    row.error_samples = int(c.counters.at("error_samples"));
    row.fallback_fraction = c.counters.at("fallback_fraction");
    row.resample_scale = c.counters.at("resample_scale");
    row.resample_aniso = c.counters.at("resample_aniso");
    row.drape_px = c.counters.at("drape_px");
    row.decision_cpu_ms = c.counters.at("decision_cpu_ms");
    if (auto t = c.tags.find("trigger"); t != c.tags.end()) row.trigger = t->second;
    decision_ms.push_back(row.decision_cpu_ms);
    if (row.key) {
      ++keyframes;
      current_key = i;
      key_ms.push_back(c.ms);
    } else {
      spr_ms.push_back(c.ms);
    }
    row.keyframe = current_key;
    if (a) {
      full_ms.push_back(a->ms);
      row.lod = *b.quality;
      row.sprite = *c.quality;
      const QualityScore &ls = row.lod, &ss = row.sprite;
      lod_psnr.push_back(ls.psnr);
      lod_ssim.push_back(ls.ssim);
      lod_flip.push_back(ls.flip);
      sp_psnr.push_back(ss.psnr);
      sp_ssim.push_back(ss.ssim);
      sp_flip.push_back(ss.flip);
      if (!row.key) {
        sp_psnr_sprite_only.push_back(ss.psnr);
        lod_psnr_sprite_only.push_back(ls.psnr);
        ++scored_sprite_frames;
      }
      ssim_above += ss.ssim > ls.ssim;
      ssim_above_sprite_frames += !row.key && ss.ssim > ls.ssim;
    } else {
      row.lod = row.sprite = {.psnr = nan, .ssim = nan, .flip = nan};
    }
    res.per_frame.push_back(std::move(row));
  }
  const int scored = int(full_ms.size());
  res.reference_frames = scored;

  // Every frame's reference drawn: the measured total; else the sampled
  // frames' mean x n (an estimate, the JSON says which).
  const double full_total = scored == n ? sum(full_ms) : mean(full_ms) * n;
  const double sprite_total = sum(sprite_ms);
  const double full_median = median(full_ms);
  const double key_median = median(key_ms), spr_median = median(spr_ms);
  // The sprite's mean score over the frames the sweeps score (every
  // `every`-th: all reference frames).
  auto mean_every = [&](double QualityScore::*figure) {
    std::vector<double> s;
    for (int i = 0; i < n; i += every) s.push_back(res.per_frame[std::size_t(i)].sprite.*figure);
    return mean(s);
  };
  res.full_total_ms = full_total;
  res.full_median_ms = full_median;
  res.lod = {.total_ms = sum(lod_ms),
             .median_ms = median(lod_ms),
             .mean_psnr = mean(lod_psnr),
             .mean_psnr_sprite_frames = mean(lod_psnr_sprite_only),
             .mean_ssim = mean(lod_ssim),
             .min_ssim = *std::min_element(lod_ssim.begin(), lod_ssim.end()),
             .mean_flip = mean(lod_flip)};
  res.sprite = {
      .total_ms = sprite_total,
      .median_ms = median(sprite_ms),
      .p99_ms = percentile(sprite_ms, 99),
      .decision_cpu_median_ms = median(decision_ms),
      .decision_cpu_p99_ms = percentile(decision_ms, 99),
      .keyframes = keyframes,
      .sprite_frames = sprite_run.count("sprite"),
      .key_median_ms = key_median,
      .sprite_median_ms = spr_median,
      .mean_psnr = mean(sp_psnr),
      .mean_psnr_sprite_frames = mean(sp_psnr_sprite_only),
      .mean_ssim = mean(sp_ssim),
      .min_ssim = *std::min_element(sp_ssim.begin(), sp_ssim.end()),
      .mean_flip = mean(sp_flip),
      .ssim_above_lod_fraction = double(ssim_above) / scored,
      .ssim_above_lod_fraction_sprite_frames =
          scored_sprite_frames > 0 ? double(ssim_above_sprite_frames) / scored_sprite_frames : 1.0};
  res.speedup = full_total / std::max(sprite_total, 1e-9);
  res.speedup_from_medians = median_speedup(n, keyframes, full_median, key_median, spr_median);
  {
    SpeedupBound& b = res.bound;
    b.f = double(keyframes) / n;
    b.r = full_median / std::max(spr_median, 1e-9);
    b.speedup_bound = 1.0 / (b.f + (1.0 - b.f) / b.r);
    b.efficiency = res.speedup / b.speedup_bound;
    b.key_over_full_median = key_median / std::max(full_median, 1e-9);
  }
  // Stalls of this shared machine (a frame over 10x its class median) weigh
  // heavily in totals; count them so a reader can tell noise from cost.
  auto stalls = [](const std::vector<double>& v) {
    const double m = median(v);
    return int(std::count_if(v.begin(), v.end(), [&](double x) { return x > 10 * m; }));
  };
  res.stalls = {stalls(full_ms), stalls(lod_ms), stalls(key_ms), stalls(spr_ms)};

  // ---- the display simulated with asynchronous keyframes, beside a synchronous one ----
  if (cfg.async) {
    AsyncComparison& ac = res.async.emplace(
        run_async_display(gl, scene, path, w, h, so, refs, every, cfg.display_hz));
    ac.main_run_mean_ssim = mean_every(&QualityScore::ssim);
    ac.main_run_mean_psnr = mean_every(&QualityScore::psnr);
    std::vector<double> sprite_ssim;
    for (int i = 0; i < n; i += every)
      if (!res.per_frame[i].key) sprite_ssim.push_back(res.per_frame[i].sprite.ssim);
    ac.main_run_mean_ssim_sprite_frames = mean(sprite_ssim);
  }

  // ---- sweeps (paper Figs. 10-12 and the coarse-mesh size) ----
  Progress sweep_progress(label + " sweeps");
  const int sweep_total =
      int(cfg.thresholds.size() + cfg.frame_counts.size() + cfg.lod_sweep.size());
  int sweep_done = 0;
  auto sweep_entry = [&](const PassResult& p, const char* method) {
    return SweepPass{.keyframes = p.keyframes,
                     .keyframe_fraction = double(p.keyframes) / n,
                     .speedup = full_total / std::max(p.total_ms, 1e-9),
                     .speedup_from_medians = median_speedup(n, p.keyframes, full_median,
                                                            p.key_median_ms, p.sprite_median_ms),
                     .total_ms = p.total_ms,
                     .key_median_ms = p.key_median_ms,
                     .sprite_median_ms = p.sprite_median_ms,
                     .mean_ssim = p.mean_ssim,
                     .measured_in = method};
  };
  const PassResult main_pass{keyframes, sprite_total, key_median, spr_median,
                             mean_every(&QualityScore::ssim)};
  // One sweep point: the main run's figures at the main setting, else a separate timed pass.
  auto sweep_point = [&](bool is_main, auto&& set) {
    if (is_main) return sweep_entry(main_pass, "main run");
    SpriteOptions o = so;
    set(o);
    return sweep_entry(sprite_pass(scene, path, w, h, o, refs, every), "separate timed pass");
  };
  for (double t : cfg.thresholds) {
    res.threshold_sweep.push_back(
        {t, sweep_point(t == cfg.threshold_px, [&](SpriteOptions& o) { o.threshold_px = t; })});
    sweep_progress(++sweep_done, sweep_total);
  }
  for (int frames : cfg.frame_counts) {
    std::vector<Camera> p = make_path(cfg.path, terrain.heights, frames, aspect);
    const int keys = simulate_keyframes(scene, p, w, h, so);
    res.frame_count_sweep.push_back({frames, keys, double(keys) / frames});
    sweep_progress(++sweep_done, sweep_total);
  }
  for (int q : cfg.lod_sweep) {
    res.lod_sweep.push_back(
        {q, sweep_point(q == cfg.lod_quads, [&](SpriteOptions& o) { o.lod_quads = q; })});
    sweep_progress(++sweep_done, sweep_total);
  }

  // ---- keyframe cache: the same path without it, a separate timed pass ----
  if (cfg.cache_bytes > 0) {
    SpriteOptions o = so;
    o.cache_bytes = 0;
    const PassResult without = sprite_pass(scene, path, w, h, o, refs, every);
    int hits = 0;
    for (const LodspriteFrame& f : res.per_frame) hits += f.trigger == "cache";
    res.cache = CacheSummary{
        .size_bytes = cfg.cache_bytes,
        .policy = to_string(cfg.cache_policy),
        .accept = cfg.cache_accept,
        .capacity_keyframes = int(cfg.cache_bytes / (std::size_t(w) * h * 8)),
        .keyframes = keyframes,
        .keyframes_without_cache = without.keyframes,
        .hits = hits,
        .saving = without.keyframes > 0 ? 1.0 - double(keyframes) / without.keyframes : 0.0,
        .mean_ssim = mean_every(&QualityScore::ssim),
        .mean_ssim_without_cache = without.mean_ssim,
        .total_ms = sprite_total,
        .total_ms_without_cache = without.total_ms};
  }

  // ---- the keyframe trigger against the other kind at the same keyframe count ----
  if (cfg.compare_trigger)
    res.trigger_comparison = compare_triggers(scene, path, w, h, so, refs, every);

  // ---- the paper's Figs. 13 and 14: one frame full / LOD / sprite, checker and real texture ----
  int fig_frame = 0;
  double worst = -1;
  for (const LodspriteFrame& f : res.per_frame)
    if (!f.key && f.error_px_exact > worst) {
      worst = f.error_px_exact;
      fig_frame = f.frame;
    }
  const int fig_key = res.per_frame[fig_frame].keyframe;
  Terrain checker = terrain;
  checker.texture = checker_texture(32, 1024);
  checker.tex_rect = {0, 0, 1, 1};
  checker.texture_name = "checker";
  for (auto [name, t] :
       {std::pair<const char*, const Terrain*>{"fig13", &checker}, {"fig14", &terrain}}) {
    std::unique_ptr<Scene> own;
    Scene* s = &scene;
    if (t != &terrain) {
      own = std::make_unique<Scene>(*t);
      s = own.get();
    }
    MeshRenderer fr(*s, w, h, 0), lr(*s, w, h, cfg.lod_quads);
    SpriteRenderer sr(*s, w, h, so);
    sr.render_keyframe(path[fig_key]);
    Frame sf = sr.render_sprite(path[fig_frame]);
    Frame ff = fr.render(path[fig_frame]), lf = lr.render(path[fig_frame]);
    const std::string base = name;
    save_png(ff.color, out.file(base + "_full.png"));
    save_png(lf.color, out.file(base + "_lod.png"));
    save_png(sf.color, out.file(base + "_sprite.png"));
    save_png(quality::difference_image(ff.color.view(), lf.color.view()),
             out.file(base + "_diff_lod.png"));
    save_png(quality::difference_image(ff.color.view(), sf.color.view()),
             out.file(base + "_diff_sprite.png"));
    const Scorer score = default_scorer(cfg.flip);
    res.figures.push_back({.name = name,
                           .texture = t->texture_name,
                           .frame = fig_frame,
                           .keyframe = fig_key,
                           .lod = score(ff, lf),
                           .sprite = score(ff, sf)});
  }
  return res;
}

}  // namespace terrasprite::cli
