// SPDX-License-Identifier: MIT
// The simulated display behind `bench lodsprite --async` (the second thread
// with viewpoint prediction that Chen et al. 1999 name as future work).
#include "lodsprite_async.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "terrasprite/experiment/experiment.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/common/stats.h"

namespace terrasprite::cli {
namespace {

using Clock = std::chrono::steady_clock;

// Per displayed frame: which keyframe it was drawn from (for the replay).
struct Shown {
  bool key = false;  // drawn as a keyframe of its own camera
  long long serial = 0;
  Camera keyframe;
};

DisplayRun display(Scene& scene, std::span<const Camera> path, int w, int h, const SpriteOptions& o,
                   double period_ms, std::vector<Shown>* shown) {
  SpriteRenderer r(scene, w, h, o);
  DisplayRun run;
  run.period_ms = period_ms;
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double, std::milli>(period_ms));
  Clock::time_point last, slot;  // the last presentation; the next frame's slot
  Experiment pass;
  pass.add({.renderer = &r,
            .name = "sprite",
            .warmup_draws = 2,  // a keyframe, then a sprite frame; then start afresh
            .after_warmup = [&] { r.reset(); },
            .annotate =
                [&](const Frame& f, FrameResult&) {
                  Clock::time_point now = Clock::now();  // drawn
                  if (period_ms > 0 && !run.frame_ms.empty()) {
                    // Presented at its slot, or at the first one after a miss;
                    // the display sleeps till then (the worker gets the CPU).
                    if (now > slot) {
                      ++run.late_frames;
                      slot += period * ((now - slot) / period + 1);
                    }
                    std::this_thread::sleep_until(slot);
                    now = slot;
                  }
                  run.frame_ms.push_back(
                      run.frame_ms.empty()
                          ? f.ms
                          : std::chrono::duration<double, std::milli>(now - last).count());
                  run.draw_ms.push_back(f.ms);
                  last = now;
                  slot = now + period;
                  run.decision_ms.push_back(r.last_decision_ms());
                  run.keyframes_in_frame += f.cls == "key";
                  if (f.cls != "key") run.sprite_ms.push_back(run.frame_ms.back());
                  if (r.last_landed()) run.landed_frames.push_back(int(run.frame_ms.size()) - 1);
                  if (shown)
                    shown->push_back({f.cls == "key", r.keyframe_serial(), r.keyframe_camera()});
                }});
  PathSource cameras(std::vector<Camera>(path.begin(), path.end()));
  pass.run(cameras, ExperimentOptions{.warmup_draws = 2});
  run.stats = r.async_stats();
  const Summary all = summarize(run.frame_ms);
  run.median_ms = all.median;
  run.p99_ms = percentile(run.frame_ms, 99);
  run.max_ms = all.max;
  run.total_ms = all.total;
  run.sprite_median_ms = median(run.sprite_ms);
  run.sprite_p99_ms = percentile(run.sprite_ms, 99);
  run.draw_median_ms = median(run.draw_ms);
  run.draw_p99_ms = percentile(run.draw_ms, 99);
  return run;
}

// The displayed frames drawn again, synchronously, from the recorded
// keyframes, and scored against the references.
void score_replay(Scene& scene, std::span<const Camera> path, int w, int h, SpriteOptions o,
                  const std::vector<Shown>& shown, const std::vector<Image>& refs, int every,
                  DisplayRun& run) {
  o.async_context = nullptr;
  SpriteRenderer r(scene, w, h, o);
  std::vector<double> ssim, psnr;
  long long serial = -1;
  for (std::size_t i = 0; i < path.size(); i += std::size_t(every)) {
    const Shown& s = shown[i];
    Frame f;
    if (s.key) {
      f = r.render_keyframe(path[i]);
      serial = -1;
    } else {
      if (s.serial != serial) r.make_keyframe(s.keyframe);
      serial = s.serial;
      f = r.render_sprite(path[i]);
    }
    const Image& ref = refs[i / std::size_t(every)];
    quality::SsimOptions so;
    so.channels = false;
    ssim.push_back(ref.rgba == f.color.rgba ? 1.0
                                            : quality::ssim(ref.view(), f.color.view(), so).ssim);
    psnr.push_back(std::min(quality::psnr(ref.view(), f.color.view()).rgb, kPsnrCapDb));
  }
  run.mean_ssim = mean(ssim);
  run.mean_psnr = mean(psnr);
}

}  // namespace

AsyncComparison run_async_display(const GlContext& gl, Scene& scene, std::span<const Camera> path,
                                  int w, int h, SpriteOptions o, const std::vector<Image>& refs,
                                  int every, double display_hz) {
  AsyncComparison c;
  c.display_hz = display_hz;
  c.async_lead = o.async_lead;
  const double period_ms = display_hz > 0 ? 1000.0 / display_hz : 0.0;
  o.async_context = nullptr;
  c.sync = display(scene, path, w, h, o, period_ms, nullptr);
  std::vector<Shown> shown;
  o.async_context = &gl;
  c.async = display(scene, path, w, h, o, period_ms, &shown);
  score_replay(scene, path, w, h, o, shown, refs, every, c.async);
  return c;
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

}  // namespace terrasprite::cli
