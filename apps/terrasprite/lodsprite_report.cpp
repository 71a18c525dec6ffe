// SPDX-License-Identifier: MIT
// Plots (gnuplot, pngcairo) and index.html for `bench lodsprite` and `demo`.
#include "lodsprite_report.h"

#include "plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "terrasprite/error.h"

namespace terrasprite::cli {
namespace {

double num(const nlohmann::json& v) {
  return v.is_number() ? v.get<double>() : 0.0;
}

// FLIP is -1 when the run skipped it.
std::string flip_text(const nlohmann::json& v) {
  return num(v) < 0 ? "n/a" : fmt::format("{:.4f}", num(v));
}

const char* kPlots = R"GP(set terminal pngcairo size 900,420 font "sans,10"
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
plot 'per_frame.dat' u "frame":"full_ms" w l lc rgb '#888888' t 'full resolution', \
     '' u "frame":"lod_ms" w l lc rgb '#2a9d8f' t 'plain LOD', \
     '' u "frame":(column("is_key")==1 ? column("ms") : 1/0) w p pt 7 ps 0.8 lc rgb 'red' t 'LOD-sprite: key', \
     '' u "frame":(column("is_key")==0 ? column("ms") : 1/0) w p pt 7 ps 0.4 lc rgb 'blue' t 'LOD-sprite: sprite'
unset logscale y
set output 'fig10_keyframes_vs_frames.png'
set title "Keyframe fraction against frame count (paper Fig. 10)"
set xlabel "frames along the same path (log)"; set ylabel "keyframe fraction"; set logscale x
plot 'frames.dat' u "frames":"keyframe_fraction" w lp pt 7 lw 1.5 t 'keyframes / frames'
set output 'fig11_keyframes_vs_threshold.png'
set title "Keyframe fraction against threshold (paper Fig. 11)"
set xlabel "threshold (pixels, log)"
plot 'threshold.dat' u "threshold_px":"keyframe_fraction" w lp pt 7 lw 1.5 t 'keyframes / frames'
set output 'fig12_speedup_vs_threshold.png'
set title "Speed-up over full resolution against threshold (paper Fig. 12)"
set ylabel "speed-up (total full / total LOD-sprite)"
plot 'threshold.dat' u "threshold_px":"speedup" w lp pt 7 lw 1.5 t 'measured (totals)', '' u "threshold_px":"speedup_from_medians" w lp pt 5 lw 1.5 t 'from per-class medians'
set output 'lod_sweep.png'
set title "Coarse mesh size at the chosen threshold"
set xlabel "coarse quads per side (log)"; set ylabel "speed-up"; set y2label "mean SSIM"; set y2tics; set ytics nomirror
plot 'lod.dat' u "lod_quads":"speedup" w lp pt 7 lw 1.5 t 'speed-up (totals)', '' u "lod_quads":"speedup_from_medians" w lp pt 6 lw 1.5 t 'speed-up (medians)', '' u "lod_quads":"mean_ssim" axes x1y2 w lp pt 5 lw 1.5 t 'mean SSIM'
unset logscale x; unset y2tics; unset y2label; set ytics mirror
set output 'quality_ssim.png'
set title "SSIM per frame against full resolution"
set xlabel "frame"; set ylabel "SSIM"
plot 'per_frame.dat' u "frame":"ssim" w l lw 1.5 t 'LOD-sprite', '' u "frame":"lod_ssim" w l lw 1.5 t 'plain LOD'
set output 'quality_psnr.png'
set title "PSNR per frame against full resolution (keyframes capped)"
set ylabel "PSNR (dB)"
plot 'per_frame.dat' u "frame":"psnr" w l lw 1.5 t 'LOD-sprite', '' u "frame":"lod_psnr" w l lw 1.5 t 'plain LOD'
set output 'quality_flip.png'
set title "Mean FLIP per frame against full resolution"
set ylabel "FLIP"
plot 'per_frame.dat' u "frame":"flip" w l lw 1.5 t 'LOD-sprite', '' u "frame":"lod_flip" w l lw 1.5 t 'plain LOD'
)GP";

std::string row(const std::string& name, const std::string& value) {
  return fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", name, value);
}

std::string pass(bool ok) {
  return ok ? "<b style='color:#1a7f37'>met</b>" : "<b style='color:#b42318'>missed</b>";
}

}  // namespace

void write_lodsprite_report(const nlohmann::json& j, OutputDir& out) {
  std::ostringstream pf, th, fr, ld;
  for (const auto& p : j["per_frame"])
    pf << fmt::format(
        "{} {} {:.4f} {:.4f} {:.4f} {:.5f} {:.5f} {:.3f} {:.5f} {:.5f} {:.3f} {:.5f} {:.5f} "
        "{:.4f}\n",
        int(p["frame"]), p["class"] == "key" ? 1 : 0, num(p["ms"]), num(p["full_ms"]),
        num(p["lod_ms"]), num(p["error_px"]), num(p["error_px_exact"]), num(p["psnr"]),
        num(p["ssim"]), num(p["flip"]), num(p["lod_psnr"]), num(p["lod_ssim"]), num(p["lod_flip"]),
        num(p["fallback_fraction"]));
  for (const auto& t : j["threshold_sweep"])
    th << fmt::format("{} {} {} {} {} {}\n", num(t["threshold_px"]), int(t["keyframes"]),
                      num(t["keyframe_fraction"]), num(t["speedup"]), num(t["mean_ssim"]),
                      num(t["speedup_from_medians"]));
  for (const auto& t : j["frame_count_sweep"])
    fr << fmt::format("{} {} {}\n", int(t["frames"]), int(t["keyframes"]),
                      num(t["keyframe_fraction"]));
  for (const auto& t : j["lod_sweep"])
    ld << fmt::format("{} {} {} {} {}\n", int(t["lod_quads"]), int(t["keyframes"]),
                      num(t["speedup"]), num(t["mean_ssim"]), num(t["speedup_from_medians"]));
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
  std::string gp = kPlots;
  const bool paper = j["metric"] == "paper";
  auto replace_all = [&](const std::string& from, const std::string& to) {
    for (std::size_t at = gp.find(from); at != std::string::npos;
         at = gp.find(from, at + to.size()))
      gp.replace(at, from.size(), to);
  };
  replace_all("THRESHOLD_COL", paper ? "error_px" : "error_px_exact");
  replace_all("THRESHOLD", fmt::format("{}", num(j["threshold_px"])));
  write_text(out.file("plots.gp"), gp);
  const std::string plot_error = run_gnuplot(out.partial().string(), "plots.gp");
  const bool plotted = plot_error.empty();
  if (!plotted)
    fmt::print(stderr, "warning: {}; the .dat and plots.gp files are kept\n", plot_error);

  const auto& s = j["sprite"];
  const auto& l = j["lod"];
  const auto& b = j["bound"];
  const auto& t = j["targets"];
  std::ostringstream h;
  h << "<!doctype html><html><head><meta charset='utf-8'><title>LOD-sprite reproduction</title>\n"
       "<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
       "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:4px "
       "8px;text-align:left}"
       "img{max-width:100%}figure{display:inline-block;margin:4px;text-align:center}figure "
       "img{width:256px}</style>"
       "</head><body>\n";
  h << "<h1>LOD-sprite terrain rendering: reproduction of Chen, Swan, Kuo, Kaufman (IEEE "
       "Visualization 1999)</h1>\n";
  h << fmt::format(
      "<p>Terrain <b>{}</b> ({} x {} samples, texture {}), {} frames at {} x {} along the paper "
      "path, "
      "coarse mesh {} x {} quads, threshold {} px ({} metric). GL: <code>{}</code>. "
      "Full resolution, plain LOD and LOD-sprite rendered interleaved frame by frame in one "
      "process; "
      "quality scored after each frame's timed spans.</p>\n",
      j["terrain"]["name"].get<std::string>(), int(j["terrain"]["samples"][0]),
      int(j["terrain"]["samples"][1]), j["terrain"]["texture"].get<std::string>(), int(j["frames"]),
      int(j["size"][0]), int(j["size"][1]), int(j["lod_quads"]), int(j["lod_quads"]),
      num(j["threshold_px"]), j["metric"].get<std::string>(), j["gl_renderer"].get<std::string>());
  if (j.contains("video"))
    h << fmt::format(
        "<h2>The flight</h2><p><video src='{0}' controls loop muted width='{1}'></video><br>"
        "LOD-sprite frames, H.264 (<a href='{0}'>{0}</a>)</p>\n",
        j["video"].get<std::string>(), std::min(int(j["size"][0]), 1024));
  h << "<h2>Summary</h2><table>\n";
  h << row("speed-up (total full / total LOD-sprite)",
           fmt::format("<b>{:.2f}x</b> (paper: 12.32x)", num(j["speedup"])));
  h << row("speed-up from per-class medians",
           fmt::format(
               "{:.2f}x (n x median full / (k x median key + (n - k) x median sprite); "
               "robust to stalls: full {}, LOD {}, key {}, sprite {} frames over 10x their median)",
               num(j["speedup_from_medians"]), int(j["stalls"]["full"]), int(j["stalls"]["lod"]),
               int(j["stalls"]["key"]), int(j["stalls"]["sprite"])));
  h << row("keyframes", fmt::format("{} of {} ({:.1f}%; paper: 28 = 6.1%)", int(s["keyframes"]),
                                    int(j["frames"]), 100 * num(b["f"])));
  h << row("r = median full / median sprite frame",
           fmt::format("{:.1f} (full {:.2f} ms, sprite {:.2f} ms, key {:.2f} ms)", num(b["r"]),
                       num(j["full"]["median_ms"]), num(s["sprite_median_ms"]),
                       num(s["key_median_ms"])));
  h << row("bound 1 / (f + (1 - f) / r)",
           fmt::format("{:.2f}x, efficiency {:.1f}%", num(b["speedup_bound"]),
                       100 * num(b["efficiency"])));
  h << row("plain LOD median frame", fmt::format("{:.2f} ms", num(l["median_ms"])));
  h << "</table><table><tr><th></th><th>mean PSNR (dB)</th><th>mean PSNR, sprite frames "
       "only</th><th>mean SSIM</th><th>min SSIM</th><th>mean FLIP</th></tr>\n";
  h << fmt::format(
      "<tr><th>plain "
      "LOD</th><td>{:.2f}</td><td>{:.2f}</td><td>{:.4f}</td><td>{:.4f}</td><td>{}</td></tr>\n",
      num(l["mean_psnr"]), num(l["mean_psnr_sprite_frames"]), num(l["mean_ssim"]),
      num(l["min_ssim"]), flip_text(l["mean_flip"]));
  h << fmt::format(
      "<tr><th>LOD-sprite</th><td>{:.2f}</td><td>{:.2f}</td><td>{:.4f}</td><td>{:.4f}</td><td>{}</"
      "td></tr></table>\n",
      num(s["mean_psnr"]), num(s["mean_psnr_sprite_frames"]), num(s["mean_ssim"]),
      num(s["min_ssim"]), flip_text(s["mean_flip"]));
  h << fmt::format(
      "<p>Keyframes are the full-resolution frame itself (PSNR capped at {} dB, SSIM 1, FLIP "
      "0).</p>\n",
      num(j["psnr_cap_db"]));
  h << "<h2>Ours vs the paper (this run)</h2>"
       "<table><tr><th></th><th>ours</th><th>paper</th></tr>\n";
  h << fmt::format(
      "<tr><th>speed-up over full resolution</th><td>{:.2f}x</td><td>12.32x</td></tr>\n",
      num(j["speedup"]));
  h << fmt::format("<tr><th>keyframes</th><td>{} of {}</td><td>28 of 460</td></tr>\n",
                   int(s["keyframes"]), int(j["frames"]));
  h << fmt::format(
      "<tr><th>r = median full / median sprite frame</th><td>{:.1f}</td><td>about 55</td></tr>\n",
      num(b["r"]));
  if (s.contains("p99_ms"))
    h << fmt::format(
        "<tr><th>p99 frame time / median sprite frame</th><td>{:.1f} ({:.2f} / {:.2f} ms)</td>"
        "<td>-</td></tr>\n",
        num(s["p99_ms"]) / std::max(num(s["sprite_median_ms"]), 1e-9), num(s["p99_ms"]),
        num(s["sprite_median_ms"]));
  h << "</table>\n";
  if (j.contains("cache")) {
    const auto& c = j["cache"];
    h << "<h2>Keyframe cache</h2><table>\n";
    h << row("budget", fmt::format("{:.0f} MB ({} keyframes), eviction {}, reuse while error &le; "
                                   "{} x threshold",
                                   num(c["size_mb"]), int(c["capacity_keyframes"]),
                                   c["policy"].get<std::string>(), num(c["accept"])));
    h << row(
        "keyframes with / without the cache",
        fmt::format("{} / {} ({:.1f}% fewer; {} reused)", int(c["keyframes"]),
                    int(c["keyframes_without_cache"]), 100 * num(c["saving"]), int(c["hits"])));
    h << row(
        "mean SSIM with / without the cache",
        fmt::format("{:.4f} / {:.4f}", num(c["mean_ssim"]), num(c["mean_ssim_without_cache"])));
    h << row(
        "sprite total with / without the cache",
        fmt::format("{:.0f} / {:.0f} ms", num(c["total_ms"]), num(c["total_ms_without_cache"])));
    h << "</table>\n";
  }
  h << "<h2>Targets: the paper's keyframe budget, speed-up and quality against plain "
       "LOD</h2><table>\n";
  h << row("keyframes at most 28", pass(t["keyframes_at_most_28"]));
  h << row("speed-up at least 90% of the bound", pass(t["efficiency_at_least_0_9"]));
  h << row(fmt::format("SSIM above plain LOD on at least 95% of frames ({:.1f}%)",
                       100 * num(s["ssim_above_lod_fraction"])),
           pass(t["ssim_above_lod_on_95pct"]));
  h << row(
      "mean PSNR above plain LOD (all frames / sprite frames only)",
      pass(t["mean_psnr_above_lod"]) + " / " + pass(t["mean_psnr_above_lod_on_sprite_frames"]));
  h << "</table>\n";
  if (plotted) {
    h << "<h2>Plots (the paper's Figs. 8-12 from our data)</h2>\n";
    for (const char* p :
         {"fig08_error.png", "fig09_time.png", "fig10_keyframes_vs_frames.png",
          "fig11_keyframes_vs_threshold.png", "fig12_speedup_vs_threshold.png", "quality_ssim.png",
          "quality_psnr.png", "quality_flip.png", "lod_sweep.png"})
      h << fmt::format("<p><img src='{}' alt='{}'></p>\n", p, p);
  } else {
    h << fmt::format(
        "<p><b>Plots not drawn:</b> {} (see gnuplot.log); the .dat and plots.gp "
        "files are here.</p>\n",
        plot_error);
  }
  h << "<h2>Sweeps</h2><table><tr><th>threshold "
       "(px)</th><th>keyframes</th><th>fraction</th><th>speed-up (totals)</th><th>speed-up "
       "(medians)</th><th>mean SSIM</th><th>measured in</th></tr>\n";
  for (const auto& x : j["threshold_sweep"])
    h << fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{:.3f}</td><td>{:.2f}</td><td>{:.2f}</td><td>{:.4f}</"
        "td><td>{}</td></tr>\n",
        num(x["threshold_px"]), int(x["keyframes"]), num(x["keyframe_fraction"]), num(x["speedup"]),
        num(x["speedup_from_medians"]), num(x["mean_ssim"]), x["measured_in"].get<std::string>());
  h << "</table><table><tr><th>frames</th><th>keyframes</th><th>fraction</th></tr>\n";
  for (const auto& x : j["frame_count_sweep"])
    h << fmt::format("<tr><td>{}</td><td>{}</td><td>{:.3f}</td></tr>\n", int(x["frames"]),
                     int(x["keyframes"]), num(x["keyframe_fraction"]));
  h << "</table><table><tr><th>coarse quads</th><th>keyframes</th><th>speed-up "
       "(totals)</th><th>speed-up (medians)</th><th>mean SSIM</th><th>measured in</th></tr>\n";
  for (const auto& x : j["lod_sweep"])
    h << fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{:.2f}</td><td>{:.2f}</td><td>{:.4f}</td><td>{}</td></tr>\n",
        int(x["lod_quads"]), int(x["keyframes"]), num(x["speedup"]), num(x["speedup_from_medians"]),
        num(x["mean_ssim"]), x["measured_in"].get<std::string>());
  h << fmt::format("</table><p>{} SSIM in the sweeps on every {} frame(s).</p>\n",
                   j["sweep_speedup_method"].get<std::string>(), int(j["sweep_score_every"]));
  for (auto [key, title] :
       {std::pair<const char*, const char*>{"fig13", "checkerboard texture (paper Fig. 13)"},
        {"fig14", "real texture (paper Fig. 14)"}}) {
    if (!j["figures"].contains(key)) continue;
    const auto& f = j["figures"][key];
    h << fmt::format(
        "<h2>Same frame, {}: frame {} (keyframe {}), the sprite frame with the largest exact "
        "error</h2>\n",
        title, int(f["frame"]), int(f["keyframe"]));
    for (auto [suffix, caption] :
         {std::pair<const char*, std::string>{"_full.png", "full resolution"},
          {"_lod.png", fmt::format("plain LOD: PSNR {:.2f}, SSIM {:.4f}", num(f["lod"]["psnr"]),
                                   num(f["lod"]["ssim"]))},
          {"_sprite.png", fmt::format("LOD-sprite: PSNR {:.2f}, SSIM {:.4f}",
                                      num(f["sprite"]["psnr"]), num(f["sprite"]["ssim"]))},
          {"_diff_lod.png", "|full - LOD| x4"},
          {"_diff_sprite.png", "|full - sprite| x4"}})
      h << fmt::format(
          "<figure><a href='{0}{1}'><img src='{0}{1}'></a><figcaption>{2}</figcaption></figure>\n",
          key, suffix, caption);
  }
  h << "<p>All numbers: <code>lodsprite.json</code>; per-frame data: "
       "<code>per_frame.dat</code>.</p></body></html>\n";
  write_text(out.file("index.html"), h.str());
}

}  // namespace terrasprite::cli
