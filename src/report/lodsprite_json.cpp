// SPDX-License-Identifier: MIT
// The LOD-sprite JSON documents from a LodspriteResult: the one place the
// contract's key names are spelled.
#include "terrasprite/report/lodsprite_json.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "terrasprite/common/stats.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/terrain_json.h"

namespace terrasprite::report {
using namespace lodsprite;
namespace {

// What made a frame a keyframe: a trigger's name, "cache" for a reused
// keyframe, "" for a sprite frame.
const char* trigger_name(const LodspriteFrame& f) {
  return f.cache_hit ? "cache" : f.trigger ? to_string(*f.trigger) : "";
}

nlohmann::json sweep_json(const SweepPass& p) {
  return {{"keyframes", p.keyframes},
          {"keyframe_fraction", p.keyframe_fraction},
          {"speedup", p.speedup},
          {"speedup_from_medians", p.speedup_from_medians},
          {"total_ms", p.total_ms},
          {"key_median_ms", p.key_median_ms},
          {"sprite_median_ms", p.sprite_median_ms},
          {"mean_ssim", p.mean_ssim},
          {"measured_in", to_string(p.measured_in)}};
}

nlohmann::json score_json(const QualityScore& q) {
  return {{"psnr", q.psnr}, {"ssim", q.ssim}, {"flip", q.flip}};
}

nlohmann::json frame_json(const LodspriteFrame& f) {
  return {{"frame", f.frame},
          {"class", frame_class_name(f.cls)},
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
          {"trigger", trigger_name(f)},
          {"keyframe", f.keyframe},
          {"psnr", number_or_null(f.sprite.psnr)},
          {"ssim", number_or_null(f.sprite.ssim)},
          {"flip", number_or_null(f.sprite.flip)},
          {"lod_psnr", number_or_null(f.lod.psnr)},
          {"lod_ssim", number_or_null(f.lod.ssim)},
          {"lod_flip", number_or_null(f.lod.flip)}};
}

nlohmann::json settings_json(const LodspriteResult& r) {
  return {{"gl_renderer", r.gl_renderer},
          {"terrain", terrain_json(r.terrain)},
          {"size", {r.width, r.height}},
          {"frames", r.frames},
          {"path", r.path},
          {"lod_quads", r.lod_quads},
          {"threshold_px", r.threshold_px},
          {"metric", to_string(r.metric)},
          {"max_fallback_fraction", r.max_fallback_fraction},
          {"sharp_px", r.sharp_px},
          {"key_margin", r.key_margin},
          {"key_supersample", r.key_supersample},
          {"shading", to_string(r.shading)},
          {"max_resample_scale", std::isfinite(r.max_resample_scale)
                                     ? nlohmann::json(r.max_resample_scale)
                                     : nlohmann::json(nullptr)},
          {"scale_trigger_axis", r.anisotropic_scale ? "worst" : "area"},
          {"scale_per_drape_px", r.scale_per_drape_px},
          {"psnr_cap_db", kPsnrCapDb},
          {"there_and_back", r.there_and_back},
          {"async", r.async.has_value()},
          {"mesh", to_string(r.mesh)},
          {"mesh_triangles", r.mesh_triangles},
          {"reference_every", r.reference_every},
          {"reference_frames", r.reference_frames},
          {"sweep_score_every", r.sweep_score_every}};
}

nlohmann::json full_json(const LodspriteResult& r) {
  return {{"total_ms", r.full_total_ms},
          {"median_ms", r.full_median_ms},
          {"frames", r.reference_frames},
          {"total_ms_method", r.reference_frames == r.frames
                                  ? "measured: the sum over every frame"
                                  : "estimated: the mean of the drawn frames x frames"}};
}

nlohmann::json lod_json(const LodSummary& l) {
  return {{"total_ms", l.total_ms},
          {"median_ms", l.median_ms},
          {"mean_psnr", l.mean_psnr},
          {"mean_psnr_sprite_frames", number_or_null(l.mean_psnr_sprite_frames)},
          {"mean_ssim", l.mean_ssim},
          {"min_ssim", l.min_ssim},
          {"mean_flip", l.mean_flip}};
}

nlohmann::json sprite_json(const SpriteSummary& s) {
  return {{"total_ms", s.total_ms},
          {"median_ms", s.median_ms},
          {"p99_ms", s.p99_ms},
          {"decision_cpu_median_ms", s.decision_cpu_median_ms},
          {"decision_cpu_p99_ms", s.decision_cpu_p99_ms},
          {"keyframes", s.keyframes},
          {"sprite_frames", s.sprite_frames},
          {"key_median_ms", s.key_median_ms},
          {"sprite_median_ms", s.sprite_median_ms},
          {"mean_psnr", s.mean_psnr},
          {"mean_psnr_sprite_frames", number_or_null(s.mean_psnr_sprite_frames)},
          {"mean_ssim", s.mean_ssim},
          {"min_ssim", s.min_ssim},
          {"mean_flip", s.mean_flip},
          {"ssim_above_lod_fraction", s.ssim_above_lod_fraction},
          {"ssim_above_lod_fraction_sprite_frames", s.ssim_above_lod_fraction_sprite_frames}};
}

nlohmann::json bound_json(const SpeedupBound& b) {
  return {{"f", b.f},
          {"r", number_or_null(b.r)},
          {"speedup_bound", number_or_null(b.speedup_bound)},
          {"efficiency", number_or_null(b.efficiency)},
          {"key_over_full_median", b.key_over_full_median}};
}

// true: met, false: missed, null: not meaningful for this run (why_not_applicable says why).
nlohmann::json targets_json(const LodspriteTargets& t) {
  nlohmann::json j = {{"paper_speedup", 12.32}, {"paper_keyframes", 28}};
  nlohmann::json why = nlohmann::json::object();
  for (const auto& [key, check] :
       {std::pair<const char*, const TargetCheck*>{"keyframes_at_most_28", &t.keyframes_at_most_28},
        {"efficiency_at_least_0_9", &t.efficiency_at_least_0_9},
        {"ssim_above_lod_on_95pct", &t.ssim_above_lod_on_95pct},
        {"mean_psnr_above_lod", &t.mean_psnr_above_lod},
        {"mean_psnr_above_lod_on_sprite_frames", &t.mean_psnr_above_lod_on_sprite_frames}}) {
    if (check->state == TargetState::kNotApplicable) {
      j[key] = nullptr;
      why[key] = check->why;
    } else {
      j[key] = check->state == TargetState::kMet;
    }
  }
  j["why_not_applicable"] = why;
  return j;
}

// The threshold, frame-count and coarse-mesh sweeps with their methods.
void add_sweeps(const LodspriteResult& r, nlohmann::json& j) {
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
  j["sweep_speedup_method"] = kSweepSpeedupMethod;
  j["frame_count_sweep_method"] =
      "keyframe decisions only: the metric on every frame, keyframes rendered";
  j["threshold_sweep"] = threshold_sweep;
  j["frame_count_sweep"] = frame_count_sweep;
  j["lod_sweep"] = lod_sweep;
}

nlohmann::json figures_json(const std::vector<FigureCompare>& figures) {
  nlohmann::json j = nlohmann::json::object();
  for (const FigureCompare& f : figures)
    j[to_string(f.name)] = {{"texture", f.texture},
                            {"frame", f.frame},
                            {"keyframe", f.keyframe},
                            {"lod", score_json(f.lod)},
                            {"sprite", score_json(f.sprite)}};
  return j;
}

nlohmann::json cache_json(const CacheSummary& c) {
  return {{"size", c.size_bytes},
          {"size_mb", double(c.size_bytes) / (1 << 20)},
          {"policy", to_string(c.policy)},
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

nlohmann::json trigger_side_json(const TriggerSide& s) {
  return {{"metric", to_string(s.metric)},
          {"threshold", s.threshold},
          {"unit", threshold_unit(s.metric)},
          {"keyframes", s.keyframes},
          {"mean_ssim", s.mean_ssim},
          {"mean_psnr", s.mean_psnr},
          {"min_ssim", s.min_ssim}};
}

nlohmann::json trigger_comparison_json(const TriggerComparison& t) {
  return {{"main", trigger_side_json(t.main)},
          {"other", trigger_side_json(t.other)},
          {"simulations", t.simulations},
          {"method",
           "the error triggers alone (scale and fallback triggers off on both sides); each side "
           "a separate timed pass scored on the same frames; other.threshold found by bisection "
           "(keyframe-only simulations) to give main's keyframe count"}};
}

}  // namespace

nlohmann::json lodsprite_json(const LodspriteResult& r) {
  nlohmann::json j = settings_json(r);
  j["full"] = full_json(r);
  j["lod"] = lod_json(r.lod);
  j["sprite"] = sprite_json(r.sprite);
  j["speedup"] = r.speedup;
  j["speedup_from_medians"] = r.speedup_from_medians;
  j["stalls"] = {{"full", r.stalls.full},
                 {"lod", r.stalls.lod},
                 {"key", r.stalls.key},
                 {"sprite", r.stalls.sprite}};
  j["bound"] = bound_json(r.bound);
  j["targets"] = targets_json(r.targets());
  nlohmann::json by_trigger = nlohmann::json::array();
  for (const KeyframeTriggerRow& t : r.keyframes_by_trigger())
    by_trigger.push_back({{"trigger", to_string(t.trigger)},
                          {"keyframes", t.keyframes},
                          {"error_median", number_or_null(t.error_median)},
                          {"error_max", number_or_null(t.error_max)},
                          {"measure_median", number_or_null(t.measure_median)},
                          {"measure_max", number_or_null(t.measure_max)}});
  j["keyframes_by_trigger"] = by_trigger;
  add_sweeps(r, j);
  j["figures"] = figures_json(r.figures);
  nlohmann::json per_frame = nlohmann::json::array();
  for (const LodspriteFrame& f : r.per_frame) per_frame.push_back(frame_json(f));
  j["per_frame"] = per_frame;
  if (!r.video.empty()) j["video"] = r.video;
  if (r.async) j["async_run"] = async_json(*r.async);
  if (r.cache) j["cache"] = cache_json(*r.cache);
  if (r.trigger_comparison)
    j["trigger_comparison"] = trigger_comparison_json(*r.trigger_comparison);
  return j;
}

nlohmann::json demo_stats_json(const LodspriteResult& r) {
  nlohmann::json frames = nlohmann::json::array();
  for (const LodspriteFrame& p : r.per_frame)
    frames.push_back({{"frame", p.frame},
                      {"class", frame_class_name(p.cls)},
                      {"ms", p.ms},
                      {"error_px", p.error_px},
                      {"error_px_exact", p.error_px_exact},
                      {"psnr", p.sprite.psnr},
                      {"ssim", p.sprite.ssim}});
  return {{"gl_renderer", r.gl_renderer},
          {"mode", "sprite"},
          {"size", {r.width, r.height}},
          {"terrain", terrain_json(r.terrain)},
          {"path", r.path},
          {"median_ms", r.sprite.median_ms},
          {"speedup", r.speedup},
          {"keyframes", r.sprite.keyframes},
          {"full", full_json(r)},
          {"lod", lod_json(r.lod)},
          {"sprite", sprite_json(r.sprite)},
          {"bound", bound_json(r.bound)},
          {"frames", frames}};
}

nlohmann::json async_json(const AsyncComparison& c) {
  auto figures = [](const DisplayRun& r) {
    return nlohmann::json{{"frames", int(r.frame_ms.size())},
                          {"median_ms", r.median_ms},
                          {"p99_ms", r.p99_ms},
                          {"max_ms", r.max_ms},
                          {"total_ms", r.total_ms},
                          {"p99_over_median", r.p99_over_median()},
                          {"keyframes_in_frame", r.keyframes_in_frame},
                          {"sprite_frames_median_ms", r.sprite_median_ms},
                          {"sprite_frames_p99_ms", r.sprite_p99_ms},
                          {"decision_cpu_median_ms", median(r.decision_ms)},
                          {"decision_cpu_p99_ms", percentile(r.decision_ms, 99)},
                          {"draw_median_ms", r.draw_median_ms},
                          {"draw_p99_ms", r.draw_p99_ms},
                          {"period_ms", r.period_ms},
                          {"late_frames", r.late_frames},
                          {"frame_ms", r.frame_ms},
                          {"draw_ms", r.draw_ms}};
  };
  nlohmann::json sync = figures(c.sync), async = figures(c.async);
  const AsyncKeyframeStats& st = c.async.stats;
  async["keyframes"] = {
      {"requested", st.requested},
      {"landed", st.landed},
      {"used", st.used},
      {"late", st.late},
      {"late_used", st.late_used},
      {"late_fraction", st.landed > 0 ? double(st.late) / double(st.landed) : 0.0},
      {"mean_latency_frames", st.mean_latency_frames}};
  async["landed_frames"] = c.async.landed_frames;
  async["mean_ssim"] = c.async.mean_ssim;
  async["mean_psnr"] = c.async.mean_psnr;
  return {{"display_hz", c.display_hz},
          {"async_lead", c.async_lead},
          {"sync_display", sync},
          {"async_display", async},
          {"p99_ms", c.async.p99_ms},
          {"p99_over_median", c.async.p99_over_median()},
          {"p99_over_sync_sprite_median", c.p99_over_sync_median()},
          {"mean_ssim", c.async.mean_ssim},
          {"mean_ssim_sync", c.main_run_mean_ssim},
          {"mean_ssim_change", c.ssim_change()},
          {"mean_ssim_sync_sprite_frames", c.main_run_mean_ssim_sprite_frames},
          {"mean_psnr", c.async.mean_psnr},
          {"mean_psnr_sync", c.main_run_mean_psnr},
          {"targets",
           {{"p99_at_most_2x_median", c.p99_target_met()},
            {"mean_ssim_within_0_005_of_sync", c.ssim_target_met()}}},
          {"method",
           "two simulated displays after the main run, each its own pass through the experiment "
           "driver with nothing read back. Paced (display_hz > 0): a frame is presented at the "
           "first refresh slot at or after its draw ends (a frame not ready by its own slot is "
           "late and waits for the next), the display sleeping until then, and the next frame "
           "starts at once; display_hz 0: every frame presented as soon as drawn. Frame time "
           "= interval between successive presentations (frame 0: its draw). sync_display: "
           "keyframes drawn inside the frame; async_display: keyframes on a second thread and "
           "GL context, requested for the camera predicted for their landing. The async "
           "frames are scored by replaying them (same keyframe cameras, same sprite "
           "cameras) with a synchronous renderer; mean_ssim_sync / mean_psnr_sync: the "
           "interleaved main run, the same frames"}};
}

}  // namespace terrasprite::report
