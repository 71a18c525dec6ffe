// SPDX-License-Identifier: MIT
// The simulated display behind `bench lodsprite --async` (the second thread
// with viewpoint prediction that Chen et al. 1999 name as future work).
#include "terrasprite/experiment/lodsprite/async_display.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "experiment/lodsprite/frame_class.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite::lodsprite {
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
                  const bool key = last_frame_class(r) == FrameClass::kKey;
                  run.keyframes_in_frame += key;
                  if (!key) run.sprite_ms.push_back(run.frame_ms.back());
                  if (r.last_landed()) run.landed_frames.push_back(int(run.frame_ms.size()) - 1);
                  if (shown) shown->push_back({key, r.keyframe_serial(), r.keyframe_camera()});
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

}  // namespace terrasprite::lodsprite
