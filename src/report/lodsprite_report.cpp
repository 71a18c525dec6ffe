// SPDX-License-Identifier: MIT
// Plots (gnuplot, pngcairo) and index.html for `bench lodsprite` and `demo`.
#include "terrasprite/report/lodsprite_report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <tuple>
#include <vector>

#include "terrasprite/common/error.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::report {
using namespace lodsprite;
namespace {

// FLIP is -1 when the run skipped it.
std::string flip_text(double flip) {
  return flip < 0 ? "n/a" : fmt::format("{:.4f}", flip);
}

// The plots of every run: error, time and quality per frame (Figs. 8-9).
const char* kFramePlots = R"GP(set terminal pngcairo size 900,420 font "sans,10"
# Columns by the names in each .dat file's header row, never by number.
set datafile columnheaders
set grid
set key outside right top
set output 'fig08_error.png'
set title "Error per frame against the keyframe in use (paper Fig. 8)"
set xlabel "frame"; set ylabel "RMS error (pixels)"
plot 'per_frame.dat' u "frame":"error_px" w l lw 1.5 t 'paper metric (Eq. 1-2)', \
     '' u "frame":"error_px_exact" w l lw 1.5 t 'exact reprojection', \
     '' u "frame":(column("is_key")==1 ? column("THRESHOLD_COL") : 1/0) w p pt 7 ps 0.8 lc rgb 'red' t 'keyframe (trigger value)', \
     THRESHOLD w l dt 2 lc rgb 'black' t 'threshold'
set output 'fig09_time.png'
set title "Time per frame by class (paper Fig. 9)"
set ylabel "ms (log)"; set logscale y
plot 'per_frame.dat' u "frame":"full_ms" w QSTYLE lc rgb '#888888' t 'full resolution', \
     '' u "frame":"lod_ms" w l lc rgb '#2a9d8f' t 'plain LOD', \
     '' u "frame":(column("is_key")==1 ? column("ms") : 1/0) w p pt 7 ps 0.8 lc rgb 'red' t 'LOD-sprite: key', \
     '' u "frame":(column("is_key")==0 ? column("ms") : 1/0) w p pt 7 ps 0.4 lc rgb 'blue' t 'LOD-sprite: sprite'
unset logscale y
set output 'quality_ssim.png'
set title "SSIM per frame against full resolution"
set xlabel "frame"; set ylabel "SSIM"
plot 'per_frame.dat' u "frame":"ssim" w QSTYLE lw 1.5 t 'LOD-sprite', '' u "frame":"lod_ssim" w QSTYLE lw 1.5 t 'plain LOD'
set output 'quality_psnr.png'
set title "PSNR per frame against full resolution (keyframes capped)"
set ylabel "PSNR (dB)"
plot 'per_frame.dat' u "frame":"psnr" w QSTYLE lw 1.5 t 'LOD-sprite', '' u "frame":"lod_psnr" w QSTYLE lw 1.5 t 'plain LOD'
set output 'quality_flip.png'
set title "Mean FLIP per frame against full resolution"
set ylabel "FLIP"
plot 'per_frame.dat' u "frame":"flip" w QSTYLE lw 1.5 t 'LOD-sprite', '' u "frame":"lod_flip" w QSTYLE lw 1.5 t 'plain LOD'
)GP";

// The frame-count sweep (Fig. 10).
const char* kFrameCountPlot = R"GP(set output 'fig10_keyframes_vs_frames.png'
YRANGE_FRAMES
XRANGE_FRAMES
set title "Keyframe fraction against frame count (paper Fig. 10)"
set xlabel "frames along the same path (log)"; set ylabel "keyframe fraction"; set logscale x
plot 'frames.dat' u "frames":"keyframe_fraction" w lp pt 7 lw 1.5 t 'keyframes / frames'
unset logscale x
set autoscale xy
)GP";

// The threshold sweep (Figs. 11-12).
const char* kThresholdPlots = R"GP(set output 'fig11_keyframes_vs_threshold.png'
YRANGE_THRESHOLD
XRANGE_THRESHOLD
set title "Keyframe fraction against threshold (paper Fig. 11)"
set xlabel "threshold (pixels, log)"; set ylabel "keyframe fraction"; set logscale x
plot 'threshold.dat' u "threshold_px":"keyframe_fraction" w lp pt 7 lw 1.5 t 'keyframes / frames'
set output 'fig12_speedup_vs_threshold.png'
YRANGE_SPEEDUP
set title "Speed-up over full resolution against threshold (paper Fig. 12)"
set ylabel "speed-up (total full / total LOD-sprite)"
plot 'threshold.dat' u "threshold_px":"speedup" w lp pt 7 lw 1.5 t 'measured (totals)', '' u "threshold_px":"speedup_from_medians" w lp pt 5 lw 1.5 t 'from per-class medians'
unset logscale x
set autoscale xy
)GP";

// The coarse-mesh sweep.
const char* kLodSweepPlot = R"GP(set output 'lod_sweep.png'
XRANGE_LOD
YRANGE_LOD
Y2RANGE_LOD
set title "Coarse mesh size at the chosen threshold"
set xlabel "coarse quads per side (log)"; set ylabel "speed-up"; set y2label "mean SSIM"; set y2tics; set ytics nomirror; set logscale x
plot 'lod.dat' u "lod_quads":"speedup" w lp pt 7 lw 1.5 t 'speed-up (totals)', '' u "lod_quads":"speedup_from_medians" w lp pt 6 lw 1.5 t 'speed-up (medians)', '' u "lod_quads":"mean_ssim" axes x1y2 w lp pt 5 lw 1.5 t 'mean SSIM'
unset logscale x; unset y2tics; unset y2label; set ytics mirror; set autoscale xy; set autoscale y2
)GP";

// The plots a run has data for, in the page's order.
std::vector<const char*> plot_files(const LodspriteResult& j) {
  std::vector<const char*> files = {"fig08_error.png", "fig09_time.png"};
  if (!j.frame_count_sweep.empty()) files.push_back("fig10_keyframes_vs_frames.png");
  if (!j.threshold_sweep.empty()) {
    files.push_back("fig11_keyframes_vs_threshold.png");
    files.push_back("fig12_speedup_vs_threshold.png");
  }
  for (const char* q : {"quality_ssim.png", "quality_psnr.png", "quality_flip.png"})
    files.push_back(q);
  if (!j.lod_sweep.empty()) files.push_back("lod_sweep.png");
  return files;
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

// The async displays' frame times, frame by frame (async.dat), and the
// gnuplot lines of their plot.
std::string async_plot(const AsyncComparison& a, OutputDir& out) {
  std::ostringstream d;
  const std::size_t n = std::min(a.sync.frame_ms.size(), a.async.frame_ms.size());
  for (std::size_t i = 0; i < n; ++i)
    d << fmt::format("{} {:.3f} {:.3f} {:.3f} {:.3f}\n", i, a.sync.frame_ms[i], a.async.frame_ms[i],
                     a.sync.draw_ms[i], a.async.draw_ms[i]);
  write_text(out.file("async.dat"),
             "frame sync_ms async_ms sync_draw_ms async_draw_ms\n" + d.str());
  const double median = a.async.median_ms, p99 = a.async.p99_ms;
  return fmt::format(
      "set output 'async_frame_time.png'\n"
      "set title 'Simulated display{}: frame time = interval between presentations'\n"
      "set xlabel 'frame'; set ylabel 'ms (log)'; set logscale y; set key top right\n"
      "plot 'async.dat' u \"frame\":\"sync_ms\" w l lc rgb '#888888' t 'synchronous keyframes', "
      "\\\n"
      "     '' u \"frame\":\"async_ms\" w l lw 1.5 lc rgb '#1f77b4' t 'async keyframes', \\\n"
      "     {:.4f} w l dt 2 lc rgb '#1f77b4' t 'async median {:.1f} ms', \\\n"
      "     {:.4f} w l dt 3 lc rgb '#d62728' t 'async p99 {:.1f} ms'\n"
      "unset logscale y\n",
      a.display_hz > 0 ? fmt::format(" at {:g} Hz", a.display_hz) : "", median, median, p99, p99);
}

// The per-frame and sweep data for gnuplot, one header row of column names each.
void write_data(const LodspriteResult& j, OutputDir& out) {
  std::ostringstream pf, th, fr, ld;
  for (const LodspriteFrame& p : j.per_frame)
    pf << fmt::format(
        "{} {} {:.4f} {:.4f} {:.4f} {:.5f} {:.5f} {:.3f} {:.5f} {:.5f} {:.3f} {:.5f} {:.5f} "
        "{:.4f}\n",
        p.frame, p.key() ? 1 : 0, p.ms, p.full_ms, p.lod_ms, p.error_px, p.error_px_exact,
        p.sprite.psnr, p.sprite.ssim, p.sprite.flip, p.lod.psnr, p.lod.ssim, p.lod.flip,
        p.fallback_fraction);
  for (const ThresholdPoint& t : j.threshold_sweep)
    th << fmt::format("{} {} {} {} {} {}\n", t.threshold_px, t.pass.keyframes,
                      t.pass.keyframe_fraction, t.pass.speedup, t.pass.mean_ssim,
                      t.pass.speedup_from_medians);
  for (const FrameCountPoint& t : j.frame_count_sweep)
    fr << fmt::format("{} {} {}\n", t.frames, t.keyframes, t.keyframe_fraction);
  for (const LodQuadsPoint& t : j.lod_sweep)
    ld << fmt::format("{} {} {} {} {}\n", t.lod_quads, t.pass.keyframes, t.pass.speedup,
                      t.pass.mean_ssim, t.pass.speedup_from_medians);
  write_text(out.file("per_frame.dat"),
             "frame is_key ms full_ms lod_ms error_px error_px_exact psnr ssim flip lod_psnr "
             "lod_ssim lod_flip fallback_fraction\n" +
                 pf.str());
  write_text(out.file("threshold.dat"),
             "threshold_px keyframes keyframe_fraction speedup mean_ssim speedup_from_medians\n" +
                 th.str());
  write_text(out.file("frames.dat"), "frames keyframes keyframe_fraction\n" + fr.str());
  write_text(out.file("lod.dat"),
             "lod_quads keyframes speedup mean_ssim speedup_from_medians\n" + ld.str());
}

// gnuplot's range of `axis` for a plotted series: autoscale, or a band around
// it when every value is the same (autoscale would warn of an empty range).
std::string axis_range(const char* axis, const std::vector<double>& v) {
  if (v.empty()) return fmt::format("set autoscale {}", axis);
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  if (*hi > *lo) return fmt::format("set autoscale {}", axis);
  const double pad = std::max(0.1 * std::abs(*lo), 0.01);
  return fmt::format("set {}range [{}:{}]", axis, *lo - pad, *hi + pad);
}

// The axis range lines of the sweep plots.
void replace_axis_ranges(const LodspriteResult& j, std::string& gp) {
  std::vector<double> frames, by_frames, thresholds, by_threshold, speedup, quads, lod_speedup,
      lod_ssim;
  for (const FrameCountPoint& t : j.frame_count_sweep) {
    frames.push_back(t.frames);
    by_frames.push_back(t.keyframe_fraction);
  }
  for (const ThresholdPoint& t : j.threshold_sweep) {
    thresholds.push_back(t.threshold_px);
    by_threshold.push_back(t.pass.keyframe_fraction);
    speedup.push_back(t.pass.speedup);
    speedup.push_back(t.pass.speedup_from_medians);
  }
  for (const LodQuadsPoint& q : j.lod_sweep) {
    quads.push_back(q.lod_quads);
    lod_speedup.push_back(q.pass.speedup);
    lod_speedup.push_back(q.pass.speedup_from_medians);
    lod_ssim.push_back(q.pass.mean_ssim);
  }
  const std::tuple<const char*, const char*, const std::vector<double>*> lines[] = {
      {"XRANGE_FRAMES", "x", &frames},          {"YRANGE_FRAMES", "y", &by_frames},
      {"XRANGE_THRESHOLD", "x", &thresholds},   {"YRANGE_THRESHOLD", "y", &by_threshold},
      {"YRANGE_SPEEDUP", "y", &speedup},        {"XRANGE_LOD", "x", &quads},
      {"Y2RANGE_LOD", "y2", &lod_ssim},         {"YRANGE_LOD", "y", &lod_speedup}};
  for (const auto& [key, axis, values] : lines) {
    const std::size_t at = gp.find(key);
    if (at != std::string::npos) gp.replace(at, std::string(key).size(), axis_range(axis, *values));
  }
}

// Writes plots.gp and runs gnuplot; returns its error line, empty on success.
std::string draw_plots(const LodspriteResult& j, OutputDir& out) {
  std::string gp = kFramePlots;
  if (!j.frame_count_sweep.empty()) gp += kFrameCountPlot;
  if (!j.threshold_sweep.empty()) gp += kThresholdPlots;
  if (!j.lod_sweep.empty()) gp += kLodSweepPlot;
  replace_axis_ranges(j, gp);
  auto replace_all = [&](const std::string& from, const std::string& to) {
    for (std::size_t at = gp.find(from); at != std::string::npos;
         at = gp.find(from, at + to.size()))
      gp.replace(at, from.size(), to);
  };
  replace_all("THRESHOLD_COL", j.metric == ErrorMetric::kPaper ? "error_px" : "error_px_exact");
  // Reference figures on every n-th frame only (NaN between): points, since
  // gnuplot breaks a line at each NaN.
  replace_all("QSTYLE", j.reference_every > 1 ? "lp pt 7 ps 0.4" : "l");
  replace_all("THRESHOLD", fmt::format("{}", j.threshold_px));
  if (j.async) gp += async_plot(*j.async, out);
  write_text(out.file("plots.gp"), gp);
  const std::string plot_error = run_gnuplot(out.partial().string(), "plots.gp");
  if (!plot_error.empty())
    fmt::print(stderr, "warning: {}; the .dat and plots.gp files are kept\n", plot_error);
  return plot_error;
}

// The same-frame figures' images: full, LOD, sprite and both differences.
void save_figures(const LodspriteResult& j, OutputDir& out) {
  for (const FigureCompare& f : j.figures) {
    const std::string base = to_string(f.name);
    save_png(f.full_image, out.file(base + "_full.png"));
    save_png(f.lod_image, out.file(base + "_lod.png"));
    save_png(f.sprite_image, out.file(base + "_sprite.png"));
    save_png(f.diff_lod_image, out.file(base + "_diff_lod.png"));
    save_png(f.diff_sprite_image, out.file(base + "_diff_sprite.png"));
  }
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
           std::string(flat(j.frame_count_sweep, [](const FrameCountPoint& p) {
                          return p.keyframe_fraction;
                        })
                            ? " Flat here: every frame count gave the same fraction."
                            : "");
  if (file == "fig11_keyframes_vs_threshold.png")
    return "Keyframes / frames at each error threshold." +
           std::string(flat(j.threshold_sweep, [](const ThresholdPoint& p) {
                          return p.pass.keyframes;
                        })
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
    h << fmt::format("<figure style='display:block'><img src='{0}' alt='{0}'><figcaption>{1}"
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
  write_data(j, out);
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
  text += fmt::format(
      "keyframes {} of {} ({}); speed-up {:.2f}x over full resolution, r {}\n",
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
