// SPDX-License-Identifier: MIT
// The paper's sweeps (its Figs. 10-12 and the coarse-mesh size), the
// keyframe-cache comparison and the same-frame figures (its Figs. 13-14).
#include "experiment/lodsprite/stages.h"

#include <algorithm>
#include <memory>
#include <utility>

#include "experiment/lodsprite/sprite_pass.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/terrain/texture_gen.h"

namespace terrasprite::lodsprite {
namespace {

SweepPass sweep_entry(const LodspriteResult& r, const PassResult& p, SweepMethod method) {
  const int n = r.frames;
  return SweepPass{.keyframes = p.keyframes,
                   .keyframe_fraction = double(p.keyframes) / n,
                   .speedup = r.full_total_ms / std::max(p.total_ms, 1e-9),
                   .speedup_from_medians = median_speedup(n, p.keyframes, r.full_median_ms,
                                                          p.key_median_ms, p.sprite_median_ms),
                   .total_ms = p.total_ms,
                   .key_median_ms = p.key_median_ms,
                   .sprite_median_ms = p.sprite_median_ms,
                   .mean_ssim = p.mean_ssim,
                   .measured_in = method};
}

// One sweep point: the main run's figures at the main setting, else a
// separate timed pass with `set` applied to the main run's sprite options.
template <typename Set>
SweepPass sweep_point(const StageContext& s, const LodspriteResult& r, bool is_main, Set&& set) {
  if (is_main) {
    const PassResult main_pass{r.sprite.keyframes, r.sprite.total_ms, r.sprite.key_median_ms,
                               r.sprite.sprite_median_ms,
                               mean_every(r, s.every, &QualityScore::ssim)};
    return sweep_entry(r, main_pass, SweepMethod::kMainRun);
  }
  SpriteOptions o = s.sprite;
  set(o);
  return sweep_entry(r, sprite_pass(s.scene, s.path, s.width, s.height, o, s.refs, s.every),
                     SweepMethod::kSeparatePass);
}

// One same-frame figure on `terrain` (the run's, or a re-textured copy).
FigureCompare figure(const StageContext& s, SameFrameFigure name, const Terrain& terrain, int frame,
                     int key) {
  std::unique_ptr<Scene> own;
  Scene* scene = &s.scene;
  if (&terrain != &s.terrain) {
    own = std::make_unique<Scene>(terrain);
    scene = own.get();
  }
  const LodspriteOptions& c = s.options;
  MeshRenderer fr(*scene, s.width, s.height, 0), lr(*scene, s.width, s.height, c.lod_quads);
  SpriteRenderer sr(*scene, s.width, s.height, s.sprite);
  sr.render_keyframe(s.path[key]);
  Frame sf = sr.render_sprite(s.path[frame]);
  Frame ff = fr.render(s.path[frame]), lf = lr.render(s.path[frame]);
  const Scorer score = default_scorer(c.flip);
  FigureCompare f{.name = name,
                  .texture = terrain.texture_name,
                  .frame = frame,
                  .keyframe = key,
                  .lod = score(ff, lf),
                  .sprite = score(ff, sf)};
  f.diff_lod_image = quality::difference_image(ff.color.view(), lf.color.view());
  f.diff_sprite_image = quality::difference_image(ff.color.view(), sf.color.view());
  f.full_image = std::move(ff.color);
  f.lod_image = std::move(lf.color);
  f.sprite_image = std::move(sf.color);
  return f;
}

}  // namespace

double median_speedup(int n, int keys, double full_median, double key_median,
                      double sprite_median) {
  const double cost = keys * key_median + (n - keys) * sprite_median;
  return cost > 0 ? n * full_median / cost : 0.0;
}

double mean_every(const LodspriteResult& r, int every, double QualityScore::*figure) {
  std::vector<double> s;
  for (int i = 0; i < r.frames; i += every) s.push_back(r.per_frame[std::size_t(i)].sprite.*figure);
  return mean(s);
}

void run_sweeps(const StageContext& s, LodspriteResult& r) {
  const LodspriteOptions& c = s.options;
  const int total = int(c.thresholds.size() + c.frame_counts.size() + c.lod_sweep.size());
  int done = 0;
  auto step = [&] {
    if (c.progress) c.progress("sweeps", ++done, total);
  };
  for (double t : c.thresholds) {
    r.threshold_sweep.push_back(
        {t, sweep_point(s, r, t == c.threshold_px, [&](SpriteOptions& o) { o.threshold_px = t; })});
    step();
  }
  const double aspect = double(s.width) / s.height;
  for (int frames : c.frame_counts) {
    std::vector<Camera> p = make_path(c.path, s.terrain.heights, frames, aspect);
    const int keys = simulate_keyframes(s.scene, p, s.width, s.height, s.sprite);
    r.frame_count_sweep.push_back({frames, keys, double(keys) / frames});
    step();
  }
  for (int q : c.lod_sweep) {
    r.lod_sweep.push_back(
        {q, sweep_point(s, r, q == c.lod_quads, [&](SpriteOptions& o) { o.lod_quads = q; })});
    step();
  }
}

CacheSummary compare_cache(const StageContext& s, const LodspriteResult& r) {
  const LodspriteOptions& c = s.options;
  SpriteOptions o = s.sprite;
  o.cache_bytes = 0;
  const PassResult without = sprite_pass(s.scene, s.path, s.width, s.height, o, s.refs, s.every);
  const int hits = int(std::count_if(r.per_frame.begin(), r.per_frame.end(),
                                     [](const LodspriteFrame& f) { return f.cache_hit; }));
  const int keyframes = r.sprite.keyframes;
  return CacheSummary{
      .size_bytes = c.cache_bytes,
      .policy = c.cache_policy,
      .accept = c.cache_accept,
      .capacity_keyframes = int(c.cache_bytes / (std::size_t(s.width) * s.height * 8)),
      .keyframes = keyframes,
      .keyframes_without_cache = without.keyframes,
      .hits = hits,
      .saving = without.keyframes > 0 ? 1.0 - double(keyframes) / without.keyframes : 0.0,
      .mean_ssim = mean_every(r, s.every, &QualityScore::ssim),
      .mean_ssim_without_cache = without.mean_ssim,
      .total_ms = r.sprite.total_ms,
      .total_ms_without_cache = without.total_ms};
}

std::vector<FigureCompare> same_frame_figures(const StageContext& s, const LodspriteResult& r) {
  int frame = 0;
  double worst = -1;
  for (const LodspriteFrame& f : r.per_frame)
    if (!f.key() && f.error_px_exact > worst) {
      worst = f.error_px_exact;
      frame = f.frame;
    }
  const int key = r.per_frame[std::size_t(frame)].keyframe;
  Terrain checker = s.terrain;
  checker.texture = checker_texture(32, 1024);
  checker.tex_rect = {0, 0, 1, 1};
  checker.texture_name = "checker";
  std::vector<FigureCompare> out;
  out.push_back(figure(s, SameFrameFigure::kFig13, checker, frame, key));
  out.push_back(figure(s, SameFrameFigure::kFig14, s.terrain, frame, key));
  return out;
}

}  // namespace terrasprite::lodsprite
