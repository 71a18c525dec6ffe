// SPDX-License-Identifier: MIT
// The hybrid walkthrough's report: JSON, the paper's Figure 4 (frame time),
// Figure 5 (triangles), Table 2 (quality at the checkpoints) and Figure 6
// (images at one checkpoint, with differences), and index.html.
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include "hybrid_bench.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/common/error.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite::cli {
namespace {

std::string dat_name(const std::string& scenario) {
  return "frames_" + scenario + ".dat";
}

/// One .dat per scenario, a row per frame: the frame's own figures, then the
/// selection's counters and the quality figures (NaN where a frame has none).
void write_frames(const HybridScenarioResult& s, OutputDir& out) {
  static constexpr std::string_view kColumns[] = {
      "frame",        "ms",           "triangles",    "triangles_min",     "triangles_max",
      "predicted_ms", "budget_ms",    "switches",     "selection_ms",      "ssim",
      "floor_ms",     "not_drawn",    "ssim_objects", "expected_ssim",     "n_mesh",
      "n_relief",     "n_octahedral", "draw_gap_ms",  "visible",           "occluded",
      "policy_ms",    "occlusion_ms", "pace",         "objects_budget_ms", "view_ms"};
  std::ostringstream f;
  f << fmt::format("{}\n", fmt::join(kColumns, " "));
  for (const FrameResult& r : s.frames) {
    auto value = [&](std::string_view k) -> std::string {
      if (k == "frame") return fmt::format("{}", r.frame);
      if (k == "ms") return fmt::format("{}", r.ms);
      if (k == "triangles") return fmt::format("{}", r.triangles);
      if (k == "ssim") return r.quality ? fmt::format("{}", r.quality->ssim) : "NaN";
      if (k == "ssim_objects") {
        if (!r.quality) return "NaN";
        const auto it = r.quality->figures.find(std::string(k));
        return it == r.quality->figures.end() ? "NaN" : fmt::format("{}", it->second);
      }
      const auto it = r.counters.find(std::string(k));
      return it == r.counters.end() ? "NaN" : fmt::format("{}", it->second);
    };
    std::vector<std::string> row;
    for (std::string_view k : kColumns) row.push_back(value(k));
    f << fmt::format("{}\n", fmt::join(row, " "));
  }
  report::write_text(out.file(dat_name(s.name)), f.str());
}

std::string plots_script(const HybridBenchResult& r) {
  std::ostringstream g;
  g << "set terminal pngcairo size 1000,440 font \"sans,10\"\nset datafile columnheaders\nset "
       "grid\n"
       "set key outside right top\n";
  g << "set output 'fig4_frame_time.png'\nset title \"Frame time per frame (paper Fig. 4), target "
    << r.target_ms << " ms\"\nset xlabel 'frame'; set ylabel 'ms (log)'; set logscale y\nplot ";
  for (const HybridScenarioResult& s : r.scenarios)
    g << "'" << dat_name(s.name) << "' u \"frame\":\"ms\" w lp pt 7 ps 0.3 t '" << s.name << "', ";
  g << r.target_ms << " w l dt 2 lw 2 lc rgb 'black' t 'target'\nunset logscale y\n";
  g << "set output 'fig5_triangles.png'\nset title 'Triangles drawn per frame (paper Fig. 5)'\n"
       "set ylabel 'object triangles (log)'; set logscale y\nplot ";
  const char* colours[] = {"#e76f51", "#2a9d8f"};
  int k = 0;
  for (const char* name : {"pm", "mixed"}) {
    const std::string d = dat_name(name), c = colours[k++];
    g << "'" << d << "' u \"frame\":\"triangles\" w l lw 2 lc rgb '" << c << "' t '" << name
      << " chosen', '" << d << "' u \"frame\":\"triangles_min\" w l dt 3 lc rgb '" << c << "' t '"
      << name << " min', '" << d << "' u \"frame\":\"triangles_max\" w l dt 2 lc rgb '" << c
      << "' t '" << name << " max'" << (k < 2 ? ", " : "\n");
  }
  return g.str();
}

/// Figure 6: each scenario's image at the checkpoint and its difference to full.
std::vector<std::string> write_figure6(const HybridBenchResult& r, OutputDir& out) {
  std::vector<std::string> files;
  if (r.figure6.empty()) return files;
  const Image& full = r.figure6.front().second;
  for (const auto& [name, img] : r.figure6) {
    save_png(img, out.file("fig6_" + name + ".png"));
    files.push_back("fig6_" + name + ".png");
    if (&img != &full && img.width == full.width && img.height == full.height) {
      save_png(quality::difference_image(full.view(), img.view()),
               out.file("fig6_" + name + "_diff.png"));
      files.push_back("fig6_" + name + "_diff.png");
    }
  }
  return files;
}

std::string scenario_table_html(const HybridBenchResult& r) {
  std::ostringstream h;
  h << "<table border=1 cellpadding=4><tr><th>scenario</th><th>median ms</th><th>p95 "
       "ms</th><th>p99 ms</th>"
       "<th>within +10%</th><th>mean SSIM</th><th>mean SSIM "
       "objects</th><th>switches/frame</th></tr>\n";
  for (const HybridScenarioResult& s : r.scenarios)
    h << fmt::format(
        "<tr><td>{}</td><td>{:.1f}</td><td>{:.1f}</td><td>{:.1f}</td><td>{:.0f}%</td><td>{:.4f}</"
        "td>"
        "<td>{:.4f}</td><td>{:.2f}</td></tr>\n",
        s.name, s.ms.median, s.ms.p95, s.ms.p99, 100 * s.within_10pct, s.mean_ssim,
        s.mean_ssim_objects, s.switches_per_frame);
  h << "</table>\n";
  return h.str();
}

}  // namespace

nlohmann::json hybrid_json(const HybridBenchResult& r) {
  nlohmann::json scenarios = nlohmann::json::array();
  for (const HybridScenarioResult& s : r.scenarios) {
    nlohmann::json cps = nlohmann::json::array();
    for (const HybridCheckpoint& c : s.checkpoints)
      cps.push_back({{"name", c.name},
                     {"frame", c.frame},
                     {"ssim", c.ssim},
                     {"ssim_objects", c.ssim_objects},
                     {"psnr", c.psnr},
                     {"flip", c.flip}});
    scenarios.push_back({{"name", s.name},
                         {"frames_drawn", s.ms.count},
                         {"median_ms", s.ms.median},
                         {"p95_ms", s.ms.p95},
                         {"p99_ms", s.ms.p99},
                         {"within_10pct", s.within_10pct},
                         {"mean_ssim", s.mean_ssim},
                         {"mean_ssim_objects", s.mean_ssim_objects},
                         {"switches_per_frame", s.switches_per_frame},
                         {"occluded_per_frame", s.occluded_per_frame},
                         {"occlusion_ms", s.occlusion_ms},
                         {"checkpoints", cps}});
  }
  const SelectionFigures& f = r.selection;
  nlohmann::json j = {{"gl_renderer", r.gl_renderer},
                      {"msaa", r.msaa},
                      {"llvmpipe_threads",
                       r.llvmpipe_threads ? nlohmann::json(*r.llvmpipe_threads) : nlohmann::json()},
                      {"target_ms", r.target_ms},
                      {"size", {r.width, r.height}},
                      {"frames", r.frames},
                      {"score_every", r.score_every},
                      {"instances", r.instances},
                      {"terrain_ms", r.terrain_ms},
                      {"full_ms_at_start", r.full_ms_at_start},
                      {"target_auto", r.target_auto},
                      {"full_triangles_max", r.full_triangles_max},
                      {"scenarios", scenarios},
                      {"selection",
                       {{"policy", f.policy},
                        {"ms_per_frame", f.ms_per_frame},
                        {"ms_p95", f.ms_p95},
                        {"policy_ms_per_frame", f.policy_ms_per_frame},
                        {"policy_ms_p95", f.policy_ms_p95},
                        {"view_ms_per_frame", f.view_ms_per_frame},
                        {"view_ms_p95", f.view_ms_p95},
                        {"objective_greedy", f.objective_greedy},
                        {"objective_optimal", f.objective_optimal},
                        {"gain_mean", f.gain_mean},
                        {"gain_max", f.gain_max},
                        {"frames", f.frames}}}};
  if (!r.quality_context.is_null()) j["quality_context"] = r.quality_context;
  return j;
}

std::string table2_markdown(const HybridBenchResult& r) {
  std::ostringstream t;
  t << "| scenario | checkpoint | frame | SSIM | SSIM objects | PSNR dB | FLIP "
       "|\n|---|---|---|---|---|---|---|\n";
  for (const HybridScenarioResult& s : r.scenarios)
    for (const HybridCheckpoint& c : s.checkpoints)
      t << fmt::format("| {} | {} | {} | {:.4f} | {:.4f} | {:.2f} | {:.4f} |\n", s.name, c.name,
                       c.frame, c.ssim, c.ssim_objects, c.psnr, c.flip);
  return t.str();
}

void write_hybrid_report(const HybridBenchResult& r, OutputDir& out) {
  for (const HybridScenarioResult& s : r.scenarios) write_frames(s, out);
  report::write_text(out.file("plots.gp"), plots_script(r));
  const std::string plot_error = report::run_gnuplot(out.partial().string(), "plots.gp");
  const std::vector<std::string> fig6 = write_figure6(r, out);
  const std::string table2 = table2_markdown(r);
  report::write_text(out.file("table2.md"), table2);
  std::ostringstream h;
  h << "<!doctype html><html><head><meta charset='utf-8'><title>Hybrid objects "
       "walkthrough</title></head><body>\n"
    << fmt::format(
           "<h1>Hybrid objects walkthrough</h1><p>{} instances, {} x {}, {} frames (full geometry "
           "and "
           "scores every {} frames), {} sample{} a pixel, target {} ms, terrain alone {:.1f} ms; "
           "{}, LP_NUM_THREADS {}.</p>\n",
           r.instances, r.width, r.height, r.frames, r.score_every, r.msaa, r.msaa > 1 ? "s" : "",
           r.target_ms, r.terrain_ms, r.gl_renderer, r.llvmpipe_threads.value_or("unset"));
  if (!plot_error.empty()) h << "<p><b>Plots missing:</b> " << plot_error << "</p>\n";
  h << scenario_table_html(r);
  h << fmt::format(
      "<p>Selection (optimal): {:.3f} ms per frame (median), p95 {:.3f} ms, of which the policy "
      "{:.3f} ms (median), p95 {:.3f} ms; viewing and pricing the instances {:.3f} ms (median), "
      "p95 {:.3f} ms (on another thread, beside the depth read-back, when culling); objective "
      "optimal {:.5f} vs greedy {:.5f} on the same frames (mean gain {:.3f}%, largest "
      "{:.3f}%).</p>\n",
      r.selection.ms_per_frame, r.selection.ms_p95, r.selection.policy_ms_per_frame,
      r.selection.policy_ms_p95, r.selection.view_ms_per_frame, r.selection.view_ms_p95,
      r.selection.objective_optimal, r.selection.objective_greedy, 100 * r.selection.gain_mean,
      100 * r.selection.gain_max);
  if (!r.calibration.empty())
    h << "<h2>Cost model calibration</h2><pre>" << r.calibration << "</pre>\n";
  h << "<h2>Figure 4: frame time</h2><img src='fig4_frame_time.png'>\n"
       "<h2>Figure 5: triangles</h2><img src='fig5_triangles.png'>\n<h2>Table 2: quality against "
       "full geometry</h2>"
       "<table border=1 "
       "cellpadding=4><tr><th>scenario</th><th>checkpoint</th><th>frame</th><th>SSIM</th>"
       "<th>SSIM objects</th><th>PSNR</th><th>FLIP</th></tr>\n";
  for (const HybridScenarioResult& s : r.scenarios)
    for (const HybridCheckpoint& c : s.checkpoints)
      h << fmt::format(
          "<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.4f}</td><td>{:.4f}</td><td>{:.2f}</td>"
          "<td>{:.4f}</td></tr>\n",
          s.name, c.name, c.frame, c.ssim, c.ssim_objects, c.psnr, c.flip);
  h << "</table>\n<h2>Figure 6: checkpoint " << r.figure6_checkpoint << "</h2>\n";
  for (const std::string& f : fig6)
    h << "<figure style='display:inline-block'><img src='" << f << "' width=420><figcaption>" << f
      << "</figcaption></figure>\n";
  h << "</body></html>\n";
  report::write_text(out.file("index.html"), h.str());
}

}  // namespace terrasprite::cli
