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
#include <numeric>

#include "cli_common.h"
#include "lodsprite_async.h"
#include "lodsprite_report.h"
#include "terrasprite/camera_path.h"
#include "terrasprite/error.h"
#include "terrasprite/experiment.h"
#include "terrasprite/gl_context.h"
#include "terrasprite/mesh_renderer.h"
#include "terrasprite/quality.h"
#include "terrasprite/sprite_renderer.h"
#include "terrasprite/terrain_gen.h"

namespace terrasprite::cli {
namespace {

double ssim_only(const Image& reference, const Image& test) {
  if (reference.rgba == test.rgba) return 1.0;
  quality::SsimOptions so;
  so.channels = false;
  return quality::ssim(reference.view(), test.view(), so).ssim;
}

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

struct PassResult {
  int keyframes = 0;
  double total_ms = 0;
  double key_median_ms = 0, sprite_median_ms = 0;
  double mean_ssim = 0;
  int cache_hits = 0;
};

// One timed LOD-sprite pass over `path` through the experiment driver; the
// kept frames are SSIM-scored against the references after the whole pass,
// so scoring threads never overlap a timed frame.
PassResult sprite_pass(Scene& scene, std::span<const Camera> path, int w, int h, SpriteOptions o,
                       const std::vector<Image>& refs, int every) {
  SpriteRenderer r(scene, w, h, o);
  PassResult p;
  std::vector<Image> kept;
  Experiment pass;
  pass.add({.renderer = &r,
            .name = "sprite",
            .warmup_draws = 2,  // a keyframe, then a sprite frame; then start afresh
            .read = ReadBack::kColor,
            .after_warmup = [&] { r.reset(); },
            .annotate = [&](const Frame&, FrameResult&) { p.cache_hits += r.last_cache_hit(); }});
  ExperimentOptions eo;
  eo.on_frame = [&](int i, const std::string&, const Frame& f) {
    if (i % every == 0) kept.push_back(f.color);
  };
  PathSource cameras(std::vector<Camera>(path.begin(), path.end()));
  const RendererRun run = pass.run(cameras, eo).run("sprite");
  p.total_ms = run.ms().total;
  p.keyframes = run.count("key");
  p.key_median_ms = run.ms("key").median;
  p.sprite_median_ms = run.ms("sprite").median;
  std::vector<double> ssims;
  for (std::size_t k = 0; k < kept.size(); ++k) ssims.push_back(ssim_only(refs[k], kept[k]));
  p.mean_ssim = mean(ssims);
  return p;
}

// Speed-up from per-class medians, robust to the machine's stalls:
// n full frames against k keyframes and n - k sprite frames.
double median_speedup(int n, int keys, double full_median, double key_median,
                      double sprite_median) {
  const double cost = keys * key_median + (n - keys) * sprite_median;
  return cost > 0 ? n * full_median / cost : 0.0;
}

// Keyframe count only: the metric decides, keyframes are rendered (their depth
// buffer feeds the visibility), sprite frames are not drawn.
int simulate_keyframes(Scene& scene, std::span<const Camera> path, int w, int h, SpriteOptions o) {
  SpriteRenderer r(scene, w, h, o);
  int keys = 0;
  for (const Camera& c : path) {
    if (!r.has_keyframe() || r.keyframe_due(r.error(c))) {
      r.make_keyframe(c);
      ++keys;
    }
  }
  return keys;
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
  if (c.async && c.cache_bytes > 0)
    throw InputError("--async with --cache: the keyframe cache is not used with async keyframes");
  if (c.sweep_score_every < 1)
    throw InputError(
        fmt::format("--sweep-score-every {}: must be at least 1", c.sweep_score_every));
}

}  // namespace

ErrorMetric parse_metric(const std::string& text) {
  if (text == "paper") return ErrorMetric::kPaper;
  if (text == "exact") return ErrorMetric::kExact;
  throw InputError(fmt::format("--metric {}: must be 'paper' or 'exact'", text));
}

const char* metric_name(ErrorMetric m) {
  return m == ErrorMetric::kPaper ? "paper" : "exact";
}

CachePolicy parse_cache_policy(const std::string& text) {
  if (text == "lru") return CachePolicy::kLeastRecentlyUsed;
  if (text == "farthest") return CachePolicy::kFarthest;
  throw InputError(fmt::format("--cache-policy {}: must be 'lru' or 'farthest'", text));
}

nlohmann::json run_lodsprite(const LodspriteConfig& cfg, const Terrain& terrain, OutputDir& out,
                             const std::string& label) {
  validate(cfg);
  const int w = cfg.width, h = cfg.height, every = cfg.sweep_score_every;
  const double aspect = double(w) / h;
  std::vector<Camera> path = make_path(cfg.path, terrain.heights, cfg.frames, aspect);
  if (cfg.there_and_back) path.insert(path.end(), path.rbegin(), path.rend());
  const int n = int(path.size());

  GlContext gl;
  Scene scene(terrain);
  MeshRenderer full(scene, w, h, 0), lod(scene, w, h, cfg.lod_quads);
  SpriteOptions so;
  so.lod_quads = cfg.lod_quads;
  so.threshold_px = cfg.threshold_px;
  so.metric = cfg.metric;
  so.max_fallback_fraction = cfg.max_fallback_fraction;
  so.max_resample_scale = cfg.max_resample_scale;
  so.sharp_px = cfg.sharp_px;
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
                                      {"decision_cpu_ms", sprite.last_decision_ms()}};
                        if (sprite.last_trigger())
                          r.tags["trigger"] = to_string(*sprite.last_trigger());
                        if (sprite.last_cache_hit()) r.tags["trigger"] = "cache";
                      }});
  std::vector<Image> refs;
  ExperimentOptions eo;
  eo.warmup_draws = 2;  // the sprite's first draw is a keyframe, its second a sprite frame
  eo.scorer = default_scorer(cfg.flip);
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

  std::vector<double> full_ms(n), lod_ms(n), sprite_ms(n), key_ms, spr_ms, decision_ms;
  std::vector<double> lod_psnr, lod_ssim, lod_flip, sp_psnr, sp_ssim, sp_flip, sp_psnr_sprite_only,
      lod_psnr_sprite_only;
  std::vector<int> key_of(n, 0);
  nlohmann::json per_frame = nlohmann::json::array();
  int keyframes = 0, current_key = 0, ssim_above = 0, ssim_above_sprite_frames = 0;
  for (int i = 0; i < n; ++i) {
    const FrameResult &a = full_run.frames[i], &b = lod_run.frames[i], &c = sprite_run.frames[i];
    full_ms[i] = a.ms;
    lod_ms[i] = b.ms;
    sprite_ms[i] = c.ms;
    const bool key = c.cls == "key";
    decision_ms.push_back(c.counters.at("decision_cpu_ms"));
    if (key) {
      ++keyframes;
      current_key = i;
      key_ms.push_back(c.ms);
    } else {
      spr_ms.push_back(c.ms);
    }
    key_of[i] = current_key;
    const QualityScore ls = *b.quality, ss = *c.quality;
    lod_psnr.push_back(ls.psnr);
    lod_ssim.push_back(ls.ssim);
    lod_flip.push_back(ls.flip);
    sp_psnr.push_back(ss.psnr);
    sp_ssim.push_back(ss.ssim);
    sp_flip.push_back(ss.flip);
    if (!key) {
      sp_psnr_sprite_only.push_back(ss.psnr);
      lod_psnr_sprite_only.push_back(ls.psnr);
    }
    ssim_above += ss.ssim > ls.ssim;
    ssim_above_sprite_frames += !key && ss.ssim > ls.ssim;
    auto trigger = c.tags.find("trigger");
    per_frame.push_back({{"frame", i},
                         {"class", c.cls},
                         {"ms", c.ms},
                         {"gpu_ms", c.gpu_ms},
                         {"full_ms", a.ms},
                         {"lod_ms", b.ms},
                         {"error_px", c.counters.at("error_px")},
                         {"error_px_exact", c.counters.at("error_px_exact")},
                         {"error_samples", int(c.counters.at("error_samples"))},
                         {"fallback_fraction", c.counters.at("fallback_fraction")},
                         {"resample_scale", c.counters.at("resample_scale")},
                         {"decision_cpu_ms", c.counters.at("decision_cpu_ms")},
                         {"trigger", trigger == c.tags.end() ? "" : trigger->second},
                         {"keyframe", current_key},
                         {"psnr", ss.psnr},
                         {"ssim", ss.ssim},
                         {"flip", ss.flip},
                         {"lod_psnr", ls.psnr},
                         {"lod_ssim", ls.ssim},
                         {"lod_flip", ls.flip}});
  }

  const double full_total = sum(full_ms), sprite_total = sum(sprite_ms);
  const double speedup = full_total / std::max(sprite_total, 1e-9);
  const double f = double(keyframes) / n;
  const double r = median(full_ms) / std::max(median(spr_ms), 1e-9);
  const double bound = 1.0 / (f + (1.0 - f) / r);
  auto mean_every = [&](const std::vector<double>& v) {
    std::vector<double> s;
    for (int i = 0; i < n; i += every) s.push_back(v[i]);
    return mean(s);
  };

  // ---- the display simulated with asynchronous keyframes, beside a synchronous one ----
  nlohmann::json async_run = nullptr;
  if (cfg.async) {
    AsyncComparison ac = run_async_display(gl, scene, path, w, h, so, refs, every);
    ac.main_run_mean_ssim = mean_every(sp_ssim);
    ac.main_run_mean_psnr = mean_every(sp_psnr);
    async_run = async_json(ac);
  }

  // ---- sweeps (paper Figs. 10-12 and the coarse-mesh size) ----
  nlohmann::json threshold_sweep = nlohmann::json::array(),
                 frame_count_sweep = nlohmann::json::array(), lod_sweep = nlohmann::json::array();
  Progress sweep_progress(label + " sweeps");
  const int sweep_total =
      int(cfg.thresholds.size() + cfg.frame_counts.size() + cfg.lod_sweep.size());
  int sweep_done = 0;
  const double full_median = median(full_ms);
  const double key_median = median(key_ms), spr_median = median(spr_ms);
  auto sweep_entry = [&](const PassResult& p, const std::string& method) {
    return nlohmann::json{
        {"keyframes", p.keyframes},
        {"keyframe_fraction", double(p.keyframes) / n},
        {"speedup", full_total / std::max(p.total_ms, 1e-9)},
        {"speedup_from_medians",
         median_speedup(n, p.keyframes, full_median, p.key_median_ms, p.sprite_median_ms)},
        {"total_ms", p.total_ms},
        {"key_median_ms", p.key_median_ms},
        {"sprite_median_ms", p.sprite_median_ms},
        {"mean_ssim", p.mean_ssim},
        {"measured_in", method}};
  };
  const PassResult main_pass{keyframes, sprite_total, key_median, spr_median, mean_every(sp_ssim)};
  for (double t : cfg.thresholds) {
    nlohmann::json e;
    if (t == cfg.threshold_px) {
      e = sweep_entry(main_pass, "main run");
    } else {
      SpriteOptions o = so;
      o.threshold_px = t;
      e = sweep_entry(sprite_pass(scene, path, w, h, o, refs, every), "separate timed pass");
    }
    e["threshold_px"] = t;
    threshold_sweep.push_back(e);
    sweep_progress(++sweep_done, sweep_total);
  }
  for (int frames : cfg.frame_counts) {
    std::vector<Camera> p = make_path(cfg.path, terrain.heights, frames, aspect);
    const int keys = simulate_keyframes(scene, p, w, h, so);
    frame_count_sweep.push_back(
        {{"frames", frames}, {"keyframes", keys}, {"keyframe_fraction", double(keys) / frames}});
    sweep_progress(++sweep_done, sweep_total);
  }
  for (int q : cfg.lod_sweep) {
    nlohmann::json e;
    if (q == cfg.lod_quads) {
      e = sweep_entry(main_pass, "main run");
    } else {
      SpriteOptions o = so;
      o.lod_quads = q;
      e = sweep_entry(sprite_pass(scene, path, w, h, o, refs, every), "separate timed pass");
    }
    e["lod_quads"] = q;
    lod_sweep.push_back(e);
    sweep_progress(++sweep_done, sweep_total);
  }

  // ---- keyframe cache: the same path without it, a separate timed pass ----
  nlohmann::json cache = nullptr;
  if (cfg.cache_bytes > 0) {
    SpriteOptions o = so;
    o.cache_bytes = 0;
    const PassResult without = sprite_pass(scene, path, w, h, o, refs, every);
    int hits = 0;
    for (const FrameResult& fr : sprite_run.frames) {
      auto t = fr.tags.find("trigger");
      hits += t != fr.tags.end() && t->second == "cache";
    }
    cache = {{"size", cfg.cache_bytes},
             {"size_mb", double(cfg.cache_bytes) / (1 << 20)},
             {"policy", to_string(cfg.cache_policy)},
             {"accept", cfg.cache_accept},
             {"capacity_keyframes", int(cfg.cache_bytes / (std::size_t(w) * h * 8))},
             {"keyframes", keyframes},
             {"keyframes_without_cache", without.keyframes},
             {"hits", hits},
             {"saving", without.keyframes > 0 ? 1.0 - double(keyframes) / without.keyframes : 0.0},
             {"mean_ssim", mean_every(sp_ssim)},
             {"mean_ssim_without_cache", without.mean_ssim},
             {"total_ms", sprite_total},
             {"total_ms_without_cache", without.total_ms},
             {"method",
              "keyframes_without_cache and mean_ssim_without_cache: a separate timed pass "
              "with the cache off on the same path, scored on the same frames as mean_ssim"}};
  }

  // ---- the paper's Figs. 13 and 14: one frame full / LOD / sprite, checker and real texture ----
  int fig_frame = 0;
  double worst = -1;
  for (int i = 0; i < n; ++i)
    if (per_frame[i]["class"] == "sprite" && double(per_frame[i]["error_px_exact"]) > worst) {
      worst = per_frame[i]["error_px_exact"];
      fig_frame = i;
    }
  Terrain checker = terrain;
  checker.texture = checker_texture(32, 1024);
  checker.tex_rect = {0, 0, 1, 1};
  checker.texture_name = "checker";
  nlohmann::json figures = nlohmann::json::object();
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
    sr.render_keyframe(path[key_of[fig_frame]]);
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
    const QualityScore ls = score(ff, lf), ss = score(ff, sf);
    figures[name] = {{"texture", t->texture_name},
                     {"frame", fig_frame},
                     {"keyframe", key_of[fig_frame]},
                     {"lod", {{"psnr", ls.psnr}, {"ssim", ls.ssim}, {"flip", ls.flip}}},
                     {"sprite", {{"psnr", ss.psnr}, {"ssim", ss.ssim}, {"flip", ss.flip}}}};
  }

  // Stalls of this shared machine (a frame over 10x its class median) weigh
  // heavily in totals; count them so a reader can tell noise from cost.
  auto stalls = [](const std::vector<double>& v) {
    const double m = median(v);
    return int(std::count_if(v.begin(), v.end(), [&](double x) { return x > 10 * m; }));
  };
  nlohmann::json j = {
      {"gl_renderer", gl.renderer()},
      {"terrain", terrain_json(terrain)},
      {"size", {w, h}},
      {"frames", n},
      {"path", cfg.path},
      {"lod_quads", cfg.lod_quads},
      {"threshold_px", cfg.threshold_px},
      {"metric", metric_name(cfg.metric)},
      {"max_fallback_fraction", cfg.max_fallback_fraction},
      {"sharp_px", cfg.sharp_px},
      {"max_resample_scale", std::isfinite(cfg.max_resample_scale)
                                 ? nlohmann::json(cfg.max_resample_scale)
                                 : nlohmann::json(nullptr)},
      {"psnr_cap_db", kPsnrCapDb},
      {"there_and_back", cfg.there_and_back},
      {"async", cfg.async},
      {"mesh", "uniform"},
      {"full", {{"total_ms", full_total}, {"median_ms", median(full_ms)}}},
      {"lod",
       {{"total_ms", sum(lod_ms)},
        {"median_ms", median(lod_ms)},
        {"mean_psnr", mean(lod_psnr)},
        {"mean_psnr_sprite_frames", mean(lod_psnr_sprite_only)},
        {"mean_ssim", mean(lod_ssim)},
        {"min_ssim", *std::min_element(lod_ssim.begin(), lod_ssim.end())},
        {"mean_flip", mean(lod_flip)}}},
      {"sprite",
       {{"total_ms", sprite_total},
        {"median_ms", median(sprite_ms)},
        {"p99_ms", percentile(sprite_ms, 99)},
        {"decision_cpu_median_ms", median(decision_ms)},
        {"decision_cpu_p99_ms", percentile(decision_ms, 99)},
        {"keyframes", keyframes},
        {"sprite_frames", sprite_run.count("sprite")},
        {"key_median_ms", key_median},
        {"sprite_median_ms", spr_median},
        {"mean_psnr", mean(sp_psnr)},
        {"mean_psnr_sprite_frames", mean(sp_psnr_sprite_only)},
        {"mean_ssim", mean(sp_ssim)},
        {"min_ssim", *std::min_element(sp_ssim.begin(), sp_ssim.end())},
        {"mean_flip", mean(sp_flip)},
        {"ssim_above_lod_fraction", double(ssim_above) / n},
        {"ssim_above_lod_fraction_sprite_frames",
         n > keyframes ? double(ssim_above_sprite_frames) / (n - keyframes) : 1.0}}},
      {"speedup", speedup},
      {"speedup_from_medians", median_speedup(n, keyframes, full_median, key_median, spr_median)},
      {"stalls",
       {{"full", stalls(full_ms)},
        {"lod", stalls(lod_ms)},
        {"key", stalls(key_ms)},
        {"sprite", stalls(spr_ms)}}},
      {"bound",
       {{"f", f},
        {"r", r},
        {"speedup_bound", bound},
        {"efficiency", speedup / bound},
        {"key_over_full_median", key_median / std::max(median(full_ms), 1e-9)}}},
      {"targets",
       {{"keyframes_at_most_28", keyframes <= 28},
        {"efficiency_at_least_0_9", speedup / bound >= 0.9},
        {"ssim_above_lod_on_95pct", double(ssim_above) / n >= 0.95},
        {"mean_psnr_above_lod", mean(sp_psnr) > mean(lod_psnr)},
        {"mean_psnr_above_lod_on_sprite_frames",
         mean(sp_psnr_sprite_only) > mean(lod_psnr_sprite_only)},
        {"paper_speedup", 12.32},
        {"paper_keyframes", 28}}},
      {"sweep_score_every", every},
      {"sweep_speedup_method",
       "speedup: measured, total frame time of the sprite pass (the main run, or a separate "
       "timed pass for other settings, scored after the pass) against the main run's "
       "full-resolution total; speedup_from_medians: derived, n x median full / (k x median "
       "key + (n - k) x median sprite) with that pass's medians"},
      {"frame_count_sweep_method",
       "keyframe decisions only: the metric on every frame, keyframes rendered"},
      {"threshold_sweep", threshold_sweep},
      {"frame_count_sweep", frame_count_sweep},
      {"lod_sweep", lod_sweep},
      {"figures", figures},
      {"per_frame", per_frame}};
  if (!cfg.video.empty()) j["video"] = cfg.video;
  if (!cache.is_null()) j["cache"] = cache;
  if (!async_run.is_null()) j["async_run"] = async_run;
  write_lodsprite_report(j, out);
  return j;
}

}  // namespace terrasprite::cli
