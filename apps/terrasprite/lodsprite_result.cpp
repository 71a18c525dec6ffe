// SPDX-License-Identifier: MIT
// The `bench lodsprite` JSON document from a LodspriteResult: the one place
// the contract's key names are spelled.
#include "lodsprite_result.h"

#include <cmath>

namespace terrasprite::cli {
namespace {

nlohmann::json sweep_json(const SweepPass& p) {
  return {{"keyframes", p.keyframes},
          {"keyframe_fraction", p.keyframe_fraction},
          {"speedup", p.speedup},
          {"speedup_from_medians", p.speedup_from_medians},
          {"total_ms", p.total_ms},
          {"key_median_ms", p.key_median_ms},
          {"sprite_median_ms", p.sprite_median_ms},
          {"mean_ssim", p.mean_ssim},
          {"measured_in", p.measured_in}};
}

nlohmann::json score_json(const QualityScore& q) {
  return {{"psnr", q.psnr}, {"ssim", q.ssim}, {"flip", q.flip}};
}

nlohmann::json frame_json(const LodspriteFrame& f) {
  return {{"frame", f.frame},
          {"class", f.key ? "key" : "sprite"},
          {"ms", f.ms},
          {"gpu_ms", f.gpu_ms},
          {"reference", f.reference},
          {"full_ms", number_or_null(f.full_ms)},
          {"lod_ms", f.lod_ms},
          {"error_px", f.error_px},
          {"error_px_exact", f.error_px_exact},
          {"error_samples", f.error_samples},
          {"fallback_fraction", f.fallback_fraction},
          {"resample_scale", f.resample_scale},
          {"resample_aniso", f.resample_aniso},
          {"drape_px", f.drape_px},
          {"decision_cpu_ms", f.decision_cpu_ms},
          {"trigger", f.trigger},
          {"keyframe", f.keyframe},
          {"psnr", number_or_null(f.sprite.psnr)},
          {"ssim", number_or_null(f.sprite.ssim)},
          {"flip", number_or_null(f.sprite.flip)},
          {"lod_psnr", number_or_null(f.lod.psnr)},
          {"lod_ssim", number_or_null(f.lod.ssim)},
          {"lod_flip", number_or_null(f.lod.flip)}};
}

}  // namespace

nlohmann::json to_json(const LodspriteResult& r) {
  const LodSummary& l = r.lod;
  const SpriteSummary& s = r.sprite;
  const LodspriteTargets t = r.targets();
  nlohmann::json threshold_sweep = nlohmann::json::array(),
                 frame_count_sweep = nlohmann::json::array(), lod_sweep = nlohmann::json::array();
  for (const ThresholdPoint& t : r.threshold_sweep) {
    nlohmann::json e = sweep_json(t.pass);
    e["threshold_px"] = t.threshold_px;
    threshold_sweep.push_back(e);
  }
  for (const FrameCountPoint& f : r.frame_count_sweep)
    frame_count_sweep.push_back({{"frames", f.frames},
                                 {"keyframes", f.keyframes},
                                 {"keyframe_fraction", f.keyframe_fraction}});
  for (const LodQuadsPoint& q : r.lod_sweep) {
    nlohmann::json e = sweep_json(q.pass);
    e["lod_quads"] = q.lod_quads;
    lod_sweep.push_back(e);
  }
  nlohmann::json figures = nlohmann::json::object();
  for (const FigureCompare& f : r.figures)
    figures[f.name] = {{"texture", f.texture},
                       {"frame", f.frame},
                       {"keyframe", f.keyframe},
                       {"lod", score_json(f.lod)},
                       {"sprite", score_json(f.sprite)}};
  nlohmann::json per_frame = nlohmann::json::array();
  for (const LodspriteFrame& f : r.per_frame) per_frame.push_back(frame_json(f));

  nlohmann::json j = {
      {"gl_renderer", r.gl_renderer},
      {"terrain", terrain_json(r.terrain)},
      {"size", {r.width, r.height}},
      {"frames", r.frames},
      {"path", r.path},
      {"lod_quads", r.lod_quads},
      {"threshold_px", r.threshold_px},
      {"metric", r.metric},
      {"max_fallback_fraction", r.max_fallback_fraction},
      {"sharp_px", r.sharp_px},
      {"key_margin", r.key_margin},
      {"key_supersample", r.key_supersample},
      {"shading", r.shading},
      {"max_resample_scale", std::isfinite(r.max_resample_scale)
                                 ? nlohmann::json(r.max_resample_scale)
                                 : nlohmann::json(nullptr)},
      {"scale_trigger_axis", r.anisotropic_scale ? "worst" : "area"},
      {"scale_per_drape_px", r.scale_per_drape_px},
      {"psnr_cap_db", kPsnrCapDb},
      {"there_and_back", r.there_and_back},
      {"async", r.async.has_value()},
      {"mesh", r.mesh},
      {"mesh_triangles", r.mesh_triangles},
      {"full",
       {{"total_ms", r.full_total_ms},
        {"median_ms", r.full_median_ms},
        {"frames", r.reference_frames},
        {"total_ms_method", r.reference_frames == r.frames
                                ? "measured: the sum over every frame"
                                : "estimated: the mean of the drawn frames x frames"}}},
      {"reference_every", r.reference_every},
      {"reference_frames", r.reference_frames},
      {"lod",
       {{"total_ms", l.total_ms},
        {"median_ms", l.median_ms},
        {"mean_psnr", l.mean_psnr},
        {"mean_psnr_sprite_frames", l.mean_psnr_sprite_frames},
        {"mean_ssim", l.mean_ssim},
        {"min_ssim", l.min_ssim},
        {"mean_flip", l.mean_flip}}},
      {"sprite",
       {{"total_ms", s.total_ms},
        {"median_ms", s.median_ms},
        {"p99_ms", s.p99_ms},
        {"decision_cpu_median_ms", s.decision_cpu_median_ms},
        {"decision_cpu_p99_ms", s.decision_cpu_p99_ms},
        {"keyframes", s.keyframes},
        {"sprite_frames", s.sprite_frames},
        {"key_median_ms", s.key_median_ms},
        {"sprite_median_ms", s.sprite_median_ms},
        {"mean_psnr", s.mean_psnr},
        {"mean_psnr_sprite_frames", s.mean_psnr_sprite_frames},
        {"mean_ssim", s.mean_ssim},
        {"min_ssim", s.min_ssim},
        {"mean_flip", s.mean_flip},
        {"ssim_above_lod_fraction", s.ssim_above_lod_fraction},
        {"ssim_above_lod_fraction_sprite_frames", s.ssim_above_lod_fraction_sprite_frames}}},
      {"speedup", r.speedup},
      {"speedup_from_medians", r.speedup_from_medians},
      {"stalls",
       {{"full", r.stalls.full},
        {"lod", r.stalls.lod},
        {"key", r.stalls.key},
        {"sprite", r.stalls.sprite}}},
      {"bound",
       {{"f", r.bound.f},
        {"r", r.bound.r},
        {"speedup_bound", r.bound.speedup_bound},
        {"efficiency", r.bound.efficiency},
        {"key_over_full_median", r.bound.key_over_full_median}}},
      {"targets",
       {{"keyframes_at_most_28", t.keyframes_at_most_28},
        {"efficiency_at_least_0_9", t.efficiency_at_least_0_9},
        {"ssim_above_lod_on_95pct", t.ssim_above_lod_on_95pct},
        {"mean_psnr_above_lod", t.mean_psnr_above_lod},
        {"mean_psnr_above_lod_on_sprite_frames", t.mean_psnr_above_lod_on_sprite_frames},
        {"paper_speedup", 12.32},
        {"paper_keyframes", 28}}},
      {"sweep_score_every", r.sweep_score_every},
      {"sweep_speedup_method", kSweepSpeedupMethod},
      {"frame_count_sweep_method",
       "keyframe decisions only: the metric on every frame, keyframes rendered"},
      {"threshold_sweep", threshold_sweep},
      {"frame_count_sweep", frame_count_sweep},
      {"lod_sweep", lod_sweep},
      {"figures", figures},
      {"per_frame", per_frame}};
  if (!r.video.empty()) j["video"] = r.video;
  if (r.async) j["async_run"] = async_json(*r.async);
  if (r.cache) {
    const CacheSummary& c = *r.cache;
    j["cache"] = {{"size", c.size_bytes},
                  {"size_mb", double(c.size_bytes) / (1 << 20)},
                  {"policy", c.policy},
                  {"accept", c.accept},
                  {"capacity_keyframes", c.capacity_keyframes},
                  {"keyframes", c.keyframes},
                  {"keyframes_without_cache", c.keyframes_without_cache},
                  {"hits", c.hits},
                  {"saving", c.saving},
                  {"mean_ssim", c.mean_ssim},
                  {"mean_ssim_without_cache", c.mean_ssim_without_cache},
                  {"total_ms", c.total_ms},
                  {"total_ms_without_cache", c.total_ms_without_cache},
                  {"method",
                   "keyframes_without_cache and mean_ssim_without_cache: a separate timed pass "
                   "with the cache off on the same path, scored on the same frames as mean_ssim"}};
  }
  if (r.trigger_comparison) {
    const TriggerComparison& t = *r.trigger_comparison;
    auto side = [](const TriggerSide& s) {
      return nlohmann::json{{"metric", s.metric},       {"threshold", s.threshold},
                            {"unit", s.unit},           {"keyframes", s.keyframes},
                            {"mean_ssim", s.mean_ssim}, {"mean_psnr", s.mean_psnr},
                            {"min_ssim", s.min_ssim}};
    };
    j["trigger_comparison"] = {
        {"main", side(t.main)},
        {"other", side(t.other)},
        {"simulations", t.simulations},
        {"method",
         "the error triggers alone (scale and fallback triggers off on both sides); each side a "
         "separate timed pass scored on the same frames; other.threshold found by bisection "
         "(keyframe-only simulations) to give main's keyframe count"}};
  }
  return j;
}

}  // namespace terrasprite::cli
