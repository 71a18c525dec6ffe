// SPDX-License-Identifier: MIT
// The gnuplot figures of a `bench lodsprite` report: their data files, the
// script, the axis ranges of flat sweeps, and the same-frame images.
#include "report/lodsprite_plots.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "terrasprite/report/plot.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::report::detail {
using namespace lodsprite;
namespace {

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
      {"XRANGE_FRAMES", "x", &frames},        {"YRANGE_FRAMES", "y", &by_frames},
      {"XRANGE_THRESHOLD", "x", &thresholds}, {"YRANGE_THRESHOLD", "y", &by_threshold},
      {"YRANGE_SPEEDUP", "y", &speedup},      {"XRANGE_LOD", "x", &quads},
      {"Y2RANGE_LOD", "y2", &lod_ssim},       {"YRANGE_LOD", "y", &lod_speedup}};
  for (const auto& [key, axis, values] : lines) {
    const std::size_t at = gp.find(key);
    if (at != std::string::npos) gp.replace(at, std::string(key).size(), axis_range(axis, *values));
  }
}

}  // namespace

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

// The per-frame and sweep data for gnuplot, one header row of column names each.
void write_plot_data(const LodspriteResult& j, OutputDir& out) {
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

}  // namespace terrasprite::report::detail
