// SPDX-License-Identifier: MIT
// index.html for `bench lodsprite` and `demo` (its figures: lodsprite_plots.cpp).
#include "terrasprite/report/lodsprite_report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "report/lodsprite_plots.h"
#include "terrasprite/common/error.h"
#include "terrasprite/report/plot.h"

namespace terrasprite::report {
using namespace lodsprite;
using detail::draw_plots;
using detail::plot_files;
using detail::save_figures;
using detail::write_plot_data;
namespace {

// FLIP is -1 when the run skipped it.
std::string flip_text(double flip) {
  return flip < 0 ? "n/a" : fmt::format("{:.4f}", flip);
}

std::string row(const std::string& name, const std::string& value) {
  return fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", name, value);
}

std::string pass(bool ok) {
  return ok ? "<b style='color:#1a7f37'>met</b>" : "<b style='color:#b42318'>missed</b>";
}

std::string pass(const TargetCheck& c) {
  if (c.state == TargetState::kNotApplicable) return fmt::format("n/a ({})", c.why);
  return pass(c.state == TargetState::kMet);
}

// A figure that may be undefined (NaN): "n/a (why)" then.
std::string figure(double v, const char* format, const char* why) {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : fmt::format("n/a ({})", why);
}

// Whether the benchmarked grid is the input's own or a resampling of it.
std::string grid_origin(const TerrainInfo& t) {
  if (!t.resampled_from) return "the input's own grid";
  return fmt::format("resampled from {} x {} by --resample", t.resampled_from->first,
                     t.resampled_from->second);
}

// The page's head, title, the flight's video (first) and what ran.
void html_intro(const LodspriteResult& j, std::ostringstream& h) {
  h << "<!doctype html><html><head><meta charset='utf-8'><title>LOD-sprite reproduction</title>\n"
       "<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
       "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:4px "
       "8px;text-align:left}"
       "img{max-width:100%}figure{display:inline-block;margin:4px;text-align:center}figure "
       "img{width:256px}</style>"
       "</head><body>\n";
  h << "<h1>LOD-sprite terrain rendering: reproduction of Chen, Swan, Kuo, Kaufman (IEEE "
       "Visualization 1999)</h1>\n";
  if (!j.video.empty())
    h << fmt::format(
        "<p><video src='{0}' controls loop muted width='{1}'></video><br>"
        "The flight: LOD-sprite frames, H.264 (<a href='{0}'>{0}</a>)</p>\n",
        j.video, std::min(j.width, 1024));
  h << fmt::format(
      "<p>Terrain <b>{}</b> ({} x {} samples, {}; texture {}), {} frames at {} x {} along the "
      "path {}, "
      "coarse mesh {} x {} quads, threshold {} {} ({} metric), {} terrain shading. GL: "
      "<code>{}</code>. "
      "Full resolution, plain LOD and LOD-sprite rendered interleaved frame by frame in one "
      "process; "
      "quality scored after each frame's timed spans.</p>\n",
      j.terrain.name, j.terrain.samples_x, j.terrain.samples_y, grid_origin(j.terrain),
      j.terrain.texture, j.frames, j.width, j.height, j.path, j.lod_quads, j.lod_quads,
      j.threshold_px, threshold_unit(j.metric), to_string(j.metric), to_string(j.shading),
      j.gl_renderer);
}

void html_summary(const LodspriteResult& j, std::ostringstream& h) {
  const SpriteSummary& s = j.sprite;
  const LodSummary& l = j.lod;
  const SpeedupBound& b = j.bound;
  h << "<h2>Summary</h2><table>\n";
  h << row("speed-up (total full / total LOD-sprite)",
           fmt::format("<b>{:.2f}x</b> (paper: 12.32x)", j.speedup));
  h << row("speed-up from per-class medians",
           fmt::format(
               "{:.2f}x (n x median full / (k x median key + (n - k) x median sprite); "
               "robust to stalls: full {}, LOD {}, key {}, sprite {} frames over 10x their median)",
               j.speedup_from_medians, j.stalls.full, j.stalls.lod, j.stalls.key, j.stalls.sprite));
  h << row("keyframes",
           fmt::format("{} of {} ({:.1f}%; paper: 28 = 6.1%)", s.keyframes, j.frames, 100 * b.f));
  h << row("r = median full / median sprite frame",
           fmt::format("{} (full {:.2f} ms, sprite {:.2f} ms, key {:.2f} ms)",
                       figure(b.r, "{:.1f}", "no sprite frames"), j.full_median_ms,
                       s.sprite_median_ms, s.key_median_ms));
  h << row("bound 1 / (f + (1 - f) / r)",
           fmt::format("{}, efficiency {}", figure(b.speedup_bound, "{:.2f}x", "no r"),
                       figure(100 * b.efficiency, "{:.1f}%", "no bound")));
  h << row("plain LOD median frame", fmt::format("{:.2f} ms", l.median_ms));
  if (j.reference_every > 1)
    h << row("full-resolution reference",
             fmt::format("drawn, timed and scored on one frame in {} only ({} of {} frames): "
                         "its total is their mean x {} (an estimate) and every quality figure "
                         "is over those frames; sprite and LOD frames all drawn and timed",
                         j.reference_every, j.reference_frames, j.frames, j.frames));
  h << "</table><table><tr><th></th><th>mean PSNR (dB)</th><th>mean PSNR, sprite frames "
       "only</th><th>mean SSIM</th><th>min SSIM</th><th>mean FLIP</th></tr>\n";
  h << fmt::format(
      "<tr><th>plain "
      "LOD</th><td>{:.2f}</td><td>{}</td><td>{:.4f}</td><td>{:.4f}</td><td>{}</td></tr>\n",
      l.mean_psnr, figure(l.mean_psnr_sprite_frames, "{:.2f}", "no sprite frames"), l.mean_ssim,
      l.min_ssim, flip_text(l.mean_flip));
  h << fmt::format(
      "<tr><th>LOD-sprite</th><td>{:.2f}</td><td>{}</td><td>{:.4f}</td><td>{:.4f}</td><td>{}</"
      "td></tr></table>\n",
      s.mean_psnr, figure(s.mean_psnr_sprite_frames, "{:.2f}", "no sprite frames"), s.mean_ssim,
      s.min_ssim, flip_text(s.mean_flip));
  h << fmt::format(
      "<p>Keyframes are the full-resolution frame itself (PSNR capped at {} dB, SSIM 1, FLIP "
      "0).</p>\n",
      kPsnrCapDb);
}

void html_against_paper(const LodspriteResult& j, std::ostringstream& h) {
  const SpriteSummary& s = j.sprite;
  h << "<h2>Ours vs the paper (this run)</h2>"
       "<table><tr><th></th><th>ours</th><th>paper</th></tr>\n";
  h << fmt::format(
      "<tr><th>speed-up over full resolution</th><td>{:.2f}x</td><td>12.32x</td></tr>\n",
      j.speedup);
  h << fmt::format("<tr><th>keyframes</th><td>{} of {}</td><td>28 of 460</td></tr>\n", s.keyframes,
                   j.frames);
  h << fmt::format(
      "<tr><th>r = median full / median sprite frame</th><td>{}</td><td>about 55</td></tr>\n",
      figure(j.bound.r, "{:.1f}", "no sprite frames"));
  h << fmt::format(
      "<tr><th>p99 frame time / median sprite frame</th><td>{:.1f} ({:.2f} / {:.2f} ms)</td>"
      "<td>-</td></tr>\n",
      s.p99_ms / std::max(s.sprite_median_ms, 1e-9), s.p99_ms, s.sprite_median_ms);
  h << "</table>\n";
}

void html_cache(const CacheSummary& c, std::ostringstream& h) {
  h << "<h2>Keyframe cache</h2><table>\n";
  h << row("budget", fmt::format("{:.0f} MB ({} keyframes), eviction {}, reuse while error &le; "
                                 "{} x threshold",
                                 double(c.size_bytes) / (1 << 20), c.capacity_keyframes,
                                 to_string(c.policy), c.accept));
  h << row("keyframes with / without the cache",
           fmt::format("{} / {} ({:.1f}% fewer; {} reused)", c.keyframes, c.keyframes_without_cache,
                       100 * c.saving, c.hits));
  h << row("mean SSIM with / without the cache",
           fmt::format("{:.4f} / {:.4f}", c.mean_ssim, c.mean_ssim_without_cache));
  h << row("sprite total with / without the cache",
           fmt::format("{:.0f} / {:.0f} ms", c.total_ms, c.total_ms_without_cache));
  h << "</table>\n";
}

void html_trigger(const TriggerComparison& t, std::ostringstream& h) {
  h << "<h2>Keyframe trigger: geometric error vs predicted image error, same keyframe "
       "count</h2><table>\n<tr><th>metric</th><th>threshold</th><th>keyframes</th><th>mean "
       "SSIM</th><th>min SSIM</th><th>mean PSNR</th></tr>\n";
  for (const TriggerSide* s : {&t.main, &t.other})
    h << fmt::format(
        "<tr><td>{}</td><td>{:.3g} {}</td><td>{}</td><td>{:.4f}</td><td>{:.4f}</td><td>{:.2f} "
        "dB</td></tr>\n",
        to_string(s->metric), s->threshold, threshold_unit(s->metric), s->keyframes, s->mean_ssim,
        s->min_ssim, s->mean_psnr);
  h << fmt::format(
      "</table><p>The error triggers alone (scale and fallback triggers off on both sides), "
      "each a separate timed pass scored on the same frames; the second "
      "trigger's threshold was found by {} keyframe-only simulations.</p>\n",
      t.simulations);
}

void html_async(const AsyncComparison& a, bool plotted, std::ostringstream& h) {
  const AsyncKeyframeStats& st = a.async.stats;
  h << "<h2>Asynchronous keyframes (simulated display, frame time = interval between "
       "presentations)</h2><table>\n";
  h << row("display", a.display_hz > 0
                          ? fmt::format("paced at {:g} Hz (a frame not ready by its slot is late "
                                        "and waits for the next)",
                                        a.display_hz)
                          : std::string("flat out (each frame presented as soon as drawn)"));
  for (auto [name, d] : {std::pair{"synchronous", &a.sync}, {"async", &a.async}}) {
    h << row(fmt::format("{} display: median / p99 / max frame", name),
             fmt::format("{:.2f} / {:.2f} / {:.1f} ms (p99 / median {:.2f})", d->median_ms,
                         d->p99_ms, d->max_ms, d->p99_over_median()));
    h << row(fmt::format("{} display: draw median / p99; late frames", name),
             fmt::format("{:.2f} / {:.2f} ms; {} of {}", d->draw_median_ms, d->draw_p99_ms,
                         d->late_frames, d->frame_ms.size()));
  }
  h << row("async keyframes: requested / used / late (used anyway); mean latency",
           fmt::format("{} / {} / {} ({}); {:.1f} frames", st.requested, st.used, st.late,
                       st.late_used, st.mean_latency_frames));
  h << row("mean SSIM async / synchronous main run",
           fmt::format("{:.4f} / {:.4f} ({:+.4f})", a.async.mean_ssim, a.main_run_mean_ssim,
                       a.ssim_change()));
  h << row("p99 at most 2x the median frame", pass(a.p99_target_met()));
  h << row("mean SSIM within 0.005 of the synchronous run", pass(a.ssim_target_met()));
  h << "</table>\n";
  if (plotted) h << "<p><img src='async_frame_time.png' alt='async frame times'></p>\n";
}

void html_targets(const LodspriteResult& j, std::ostringstream& h) {
  h << "<h2>Targets: the paper's keyframe budget, speed-up and quality against plain "
       "LOD</h2><table>\n";
  const LodspriteTargets t = j.targets();
  h << row("keyframes at most 28", pass(t.keyframes_at_most_28));
  h << row("speed-up at least 90% of the bound", pass(t.efficiency_at_least_0_9));
  h << row(fmt::format("SSIM above plain LOD on at least 95% of frames ({:.1f}%)",
                       100 * j.sprite.ssim_above_lod_fraction),
           pass(t.ssim_above_lod_on_95pct));
  h << row("mean PSNR above plain LOD (all frames / sprite frames only)",
           pass(t.mean_psnr_above_lod) + " / " + pass(t.mean_psnr_above_lod_on_sprite_frames));
  h << "</table>\n";
}

// Whether every value of a sweep is the same (its plot is a flat line).
template <typename Point, typename Get>
bool flat(const std::vector<Point>& points, Get get) {
  return std::all_of(points.begin(), points.end(),
                     [&](const Point& p) { return get(p) == get(points.front()); });
}

// What a plot shows and how to read it, below it on the page.
std::string plot_caption(const LodspriteResult& j, const std::string& file) {
  const std::string unit = threshold_unit(j.metric);
  if (file == "fig08_error.png")
    return fmt::format(
        "Each frame's error against the keyframe in use ({} metric and the exact reprojection), "
        "the threshold ({} {}) dashed; red points: keyframes at the value that fired them. A "
        "keyframe well below the threshold came from another trigger (table below).",
        to_string(j.metric), j.threshold_px, unit);
  if (file == "fig09_time.png")
    return "Frame time per class, log scale: full resolution (grey), plain LOD, LOD-sprite "
           "keyframes (red) and sprite frames (blue).";
  if (file == "fig10_keyframes_vs_frames.png")
    return "Keyframes / frames when the same path is flown with more or fewer frames: smaller "
           "steps between frames give fewer keyframes per frame." +
           std::string(flat(j.frame_count_sweep,
                            [](const FrameCountPoint& p) { return p.keyframe_fraction; })
                           ? " Flat here: every frame count gave the same fraction."
                           : "");
  if (file == "fig11_keyframes_vs_threshold.png")
    return "Keyframes / frames at each error threshold." +
           std::string(
               flat(j.threshold_sweep, [](const ThresholdPoint& p) { return p.pass.keyframes; })
                   ? " Flat here: every threshold gave the same keyframes, so the "
                     "error trigger did not decide them (see the table of triggers)."
                   : "");
  if (file == "fig12_speedup_vs_threshold.png")
    return "Speed-up over full resolution at each threshold: measured from totals, and derived "
           "from the per-class medians.";
  if (file == "lod_sweep.png")
    return "Speed-up (left axis) and mean SSIM (right axis) against the coarse mesh's quads per "
           "side, at the chosen threshold.";
  return "Per frame against full resolution: LOD-sprite and plain LOD (keyframes are full "
         "resolution itself, so they score perfectly).";
}

// Which trigger fired each keyframe, and at what values.
void html_keyframe_triggers(const LodspriteResult& j, std::ostringstream& h) {
  h << fmt::format(
      "<h2>Keyframes by trigger</h2><table><tr><th>trigger</th><th>keyframes</th><th>error when "
      "fired, median / max ({}; threshold {} {})</th><th>trigger's measure, median / max</th>"
      "</tr>\n",
      to_string(j.metric), j.threshold_px, threshold_unit(j.metric));
  for (const KeyframeTriggerRow& r : j.keyframes_by_trigger()) {
    const char* measure = r.trigger == Trigger::kScale      ? "resample scale"
                          : r.trigger == Trigger::kFallback ? "fallback fraction"
                          : r.trigger == Trigger::kError    ? "error"
                                                            : "";
    h << fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{} / {}</td><td>{}</td></tr>\n", to_string(r.trigger),
        r.keyframes, figure(r.error_median, "{:.3g}", "none"),
        figure(r.error_max, "{:.3g}", "none"),
        *measure ? fmt::format("{} {} / {}", measure, figure(r.measure_median, "{:.3g}", "none"),
                               figure(r.measure_max, "{:.3g}", "none"))
                 : std::string("-"));
  }
  h << fmt::format(
      "</table><p>first: the flight's first frame; error: the error passed the threshold; "
      "scale: the keyframe's pixels were stretched past {} (rising with plain LOD's drape "
      "displacement); fallback: {}. Cache reuses are sprite frames and not counted.</p>\n",
      j.max_resample_scale,
      j.max_fallback_fraction < 1
          ? fmt::format("over {} of the in-view quads fell back to the drape texture",
                        j.max_fallback_fraction)
          : std::string("off (--fallback-trigger 1)"));
}

void html_plots(const LodspriteResult& j, const std::string& plot_error, std::ostringstream& h) {
  if (!plot_error.empty()) {
    h << fmt::format(
        "<p><b>Plots not drawn:</b> {} (see gnuplot.log); the .dat and plots.gp "
        "files are here.</p>\n",
        plot_error);
    return;
  }
  h << "<h2>Plots (the paper's Figs. 8-12 from our data)</h2>\n";
  for (const char* p : plot_files(j))
    h << fmt::format(
        "<figure style='display:block'><img src='{0}' alt='{0}'><figcaption>{1}"
        "</figcaption></figure>\n",
        p, plot_caption(j, p));
}

void html_sweeps(const LodspriteResult& j, std::ostringstream& h) {
  if (j.threshold_sweep.empty() && j.frame_count_sweep.empty() && j.lod_sweep.empty()) {
    h << "<h2>Sweeps</h2><p>Not run (the paper's Figs. 10-12): <code>terrasprite demo "
         "--sweeps</code> or <code>terrasprite bench lodsprite</code> runs them.</p>\n";
    return;
  }
  h << "<h2>Sweeps</h2><table><tr><th>threshold "
       "(px)</th><th>keyframes</th><th>fraction</th><th>speed-up (totals)</th><th>speed-up "
       "(medians)</th><th>mean SSIM</th><th>measured in</th></tr>\n";
  for (const ThresholdPoint& t : j.threshold_sweep) {
    const SweepPass& x = t.pass;
    h << fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{:.3f}</td><td>{:.2f}</td><td>{:.2f}</td><td>{:.4f}</"
        "td><td>{}</td></tr>\n",
        t.threshold_px, x.keyframes, x.keyframe_fraction, x.speedup, x.speedup_from_medians,
        x.mean_ssim, to_string(x.measured_in));
  }
  h << "</table><table><tr><th>frames</th><th>keyframes</th><th>fraction</th></tr>\n";
  for (const FrameCountPoint& x : j.frame_count_sweep)
    h << fmt::format("<tr><td>{}</td><td>{}</td><td>{:.3f}</td></tr>\n", x.frames, x.keyframes,
                     x.keyframe_fraction);
  h << "</table><table><tr><th>coarse quads</th><th>keyframes</th><th>speed-up "
       "(totals)</th><th>speed-up (medians)</th><th>mean SSIM</th><th>measured in</th></tr>\n";
  for (const LodQuadsPoint& q : j.lod_sweep) {
    const SweepPass& x = q.pass;
    h << fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{:.2f}</td><td>{:.2f}</td><td>{:.4f}</td><td>{}</td></tr>\n",
        q.lod_quads, x.keyframes, x.speedup, x.speedup_from_medians, x.mean_ssim,
        to_string(x.measured_in));
  }
  h << fmt::format("</table><p>{} SSIM in the sweeps on every {} frame(s).</p>\n",
                   kSweepSpeedupMethod, j.sweep_score_every);
}

void html_figures(const LodspriteResult& j, std::ostringstream& h) {
  for (const FigureCompare& f : j.figures) {
    const char* title = f.name == SameFrameFigure::kFig13 ? "checkerboard texture (paper Fig. 13)"
                                                          : "real texture (paper Fig. 14)";
    h << fmt::format(
        "<h2>Same frame, {}: frame {} (keyframe {}), the sprite frame with the largest exact "
        "error</h2>\n",
        title, f.frame, f.keyframe);
    for (auto [suffix, caption] :
         {std::pair<const char*, std::string>{"_full.png", "full resolution"},
          {"_lod.png", fmt::format("plain LOD: PSNR {:.2f}, SSIM {:.4f}", f.lod.psnr, f.lod.ssim)},
          {"_sprite.png",
           fmt::format("LOD-sprite: PSNR {:.2f}, SSIM {:.4f}", f.sprite.psnr, f.sprite.ssim)},
          {"_diff_lod.png", "|full - LOD| x4"},
          {"_diff_sprite.png", "|full - sprite| x4"}})
      h << fmt::format(
          "<figure><a href='{0}{1}'><img src='{0}{1}'></a><figcaption>{2}</figcaption></figure>\n",
          to_string(f.name), suffix, caption);
  }
}

}  // namespace

void write_lodsprite_report(const LodspriteResult& j, OutputDir& out) {
  save_figures(j, out);
  write_plot_data(j, out);
  const std::string plot_error = draw_plots(j, out);
  std::ostringstream h;
  html_intro(j, h);
  html_summary(j, h);
  html_against_paper(j, h);
  if (j.cache) html_cache(*j.cache, h);
  if (j.trigger_comparison) html_trigger(*j.trigger_comparison, h);
  if (j.async) html_async(*j.async, plot_error.empty(), h);
  html_targets(j, h);
  html_keyframe_triggers(j, h);
  html_plots(j, plot_error, h);
  html_sweeps(j, h);
  html_figures(j, h);
  h << "<p>All numbers: <code>lodsprite.json</code>; per-frame data: "
       "<code>per_frame.dat</code>.</p></body></html>\n";
  write_text(out.file("index.html"), h.str());
}

namespace {
std::string target_word(const TargetCheck& c) {
  return c.state == TargetState::kMet      ? "met"
         : c.state == TargetState::kMissed ? "missed"
                                           : "n/a (" + c.why + ")";
}
}  // namespace

std::string lodsprite_summary_text(const LodspriteResult& r) {
  std::string text = fmt::format(
      "bench lodsprite: {} ({} x {} samples, {}), {} frames at {}x{}, threshold {} {}\n",
      r.terrain.name, r.terrain.samples_x, r.terrain.samples_y, grid_origin(r.terrain), r.frames,
      r.width, r.height, r.threshold_px, threshold_unit(r.metric));
  std::vector<std::string> triggers;
  for (const KeyframeTriggerRow& t : r.keyframes_by_trigger())
    triggers.push_back(fmt::format("{} {}", t.keyframes, to_string(t.trigger)));
  text += fmt::format("keyframes {} of {} ({}); speed-up {:.2f}x over full resolution, r {}\n",
                      r.sprite.keyframes, r.frames, fmt::join(triggers, ", "), r.speedup,
                      figure(r.bound.r, "{:.1f}", "no sprite frames"));
  const LodspriteTargets t = r.targets();
  text += fmt::format(
      "targets: keyframes <= 28 {}; efficiency >= 0.9 {}; SSIM above LOD on 95% {}; mean PSNR "
      "above LOD {}\n",
      target_word(t.keyframes_at_most_28), target_word(t.efficiency_at_least_0_9),
      target_word(t.ssim_above_lod_on_95pct), target_word(t.mean_psnr_above_lod));
  return text;
}

}  // namespace terrasprite::report
