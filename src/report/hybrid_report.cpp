// SPDX-License-Identifier: MIT
// The hybrid walkthrough's report: JSON, the paper's Figure 4 (frame time),
// Figure 5 (triangles), Table 2 (quality at the checkpoints) and Figure 6
// (images at one checkpoint, with differences), and index.html; the
// controller replay's JSON and table.
#include "terrasprite/report/hybrid_report.h"

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <string_view>
#include <vector>

#include "terrasprite/common/error.h"
#include "terrasprite/objects/object_renderer.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::report {
namespace {

/// A number as the .dat files write it.
std::string dat_number(double v) {
  return fmt::format("{}", v);
}

/// A column of the .dat files: its header name and its value in a frame
/// ("NaN" where the frame has none).
struct DatColumn {
  const char* name;
  std::function<std::string(const HybridFrame&)> value;
};

/// A column of the selection's figures (NaN where the frame has none).
DatColumn selection_column(const char* name, double (*field)(const HybridFrameStats&)) {
  return {name, [field](const HybridFrame& f) -> std::string {
            return f.selection ? dat_number(field(*f.selection)) : "NaN";
          }};
}

/// The columns in the order the files have them.
const std::vector<DatColumn>& dat_columns() {
  using S = HybridFrameStats;
  static const std::vector<DatColumn> columns = {
      {"frame", [](const HybridFrame& f) { return fmt::format("{}", f.drawn.frame); }},
      {"ms", [](const HybridFrame& f) { return dat_number(f.drawn.ms); }},
      {"triangles", [](const HybridFrame& f) { return fmt::format("{}", f.drawn.triangles); }},
      selection_column("triangles_min", [](const S& s) { return double(s.triangles_min); }),
      selection_column("triangles_max", [](const S& s) { return double(s.triangles_max); }),
      selection_column("predicted_ms", [](const S& s) { return double(s.predicted_ms); }),
      selection_column("budget_ms", [](const S& s) { return double(s.budget_ms); }),
      selection_column("switches", [](const S& s) { return double(s.switches); }),
      selection_column("selection_ms", [](const S& s) { return double(s.selection_ms); }),
      {"ssim",
       [](const HybridFrame& f) -> std::string {
         return f.drawn.quality ? dat_number(f.drawn.quality->ssim) : "NaN";
       }},
      selection_column("floor_ms", [](const S& s) { return double(s.floor_ms); }),
      selection_column("not_drawn", [](const S& s) { return double(s.not_drawn); }),
      {"ssim_objects",
       [](const HybridFrame& f) -> std::string {
         return f.ssim_objects ? dat_number(*f.ssim_objects) : "NaN";
       }},
      selection_column("expected_ssim", [](const S& s) { return double(s.expected_ssim); }),
      selection_column("n_mesh", [](const S& s) { return double(s.instances_by_kind[0]); }),
      selection_column("n_relief", [](const S& s) { return double(s.instances_by_kind[1]); }),
      selection_column("n_octahedral", [](const S& s) { return double(s.instances_by_kind[2]); }),
      selection_column("draw_gap_ms", [](const S& s) { return double(s.draw_gap_ms); }),
      selection_column("visible", [](const S& s) { return double(s.visible); }),
      selection_column("occluded", [](const S& s) { return double(s.occluded); }),
      selection_column("policy_ms", [](const S& s) { return double(s.policy_ms); }),
      selection_column("occlusion_ms", [](const S& s) { return double(s.occlusion_ms); }),
      selection_column("pace", [](const S& s) { return double(s.pace); }),
      selection_column("objects_budget_ms", [](const S& s) { return double(s.objects_budget_ms); }),
      selection_column("view_ms", [](const S& s) { return double(s.view_ms); }),
  };
  return columns;
}

std::string dat_name(WalkScenario s) {
  return std::string("frames_") + walk_scenario_name(s) + ".dat";
}

/// One .dat per scenario, a row per frame: the frame's own figures, the
/// selection's and the quality figures (NaN where a frame has none).
void write_frames(const HybridScenarioResult& s, OutputDir& out) {
  std::ostringstream f;
  std::vector<std::string> row;
  for (const DatColumn& c : dat_columns()) row.push_back(c.name);
  f << fmt::format("{}\n", fmt::join(row, " "));
  for (const HybridFrame& frame : s.frames) {
    row.clear();
    for (const DatColumn& c : dat_columns()) row.push_back(c.value(frame));
    f << fmt::format("{}\n", fmt::join(row, " "));
  }
  write_text(out.file(dat_name(s.scenario)), f.str());
}

std::string plots_script(const HybridBenchResult& r) {
  std::ostringstream g;
  g << "set terminal pngcairo size 1000,440 font \"sans,10\"\nset datafile columnheaders\nset "
       "grid\n"
       "set key outside right top\n";
  g << "set output 'fig4_frame_time.png'\nset title \"Frame time per frame (paper Fig. 4), target "
    << r.target_ms << " ms\"\nset xlabel 'frame'; set ylabel 'ms (log)'; set logscale y\nplot ";
  for (const HybridScenarioResult& s : r.scenarios)
    g << "'" << dat_name(s.scenario) << "' u \"frame\":\"ms\" w lp pt 7 ps 0.3 t '"
      << walk_scenario_name(s.scenario) << "', ";
  g << r.target_ms << " w l dt 2 lw 2 lc rgb 'black' t 'target'\nunset logscale y\n";
  g << "set output 'fig5_triangles.png'\nset title 'Triangles drawn per frame (paper Fig. 5)'\n"
       "set ylabel 'object triangles (log)'; set logscale y\nplot ";
  const char* colours[] = {"#e76f51", "#2a9d8f"};
  int k = 0;
  for (const WalkScenario scenario : {WalkScenario::kPm, WalkScenario::kMixed}) {
    const char* name = walk_scenario_name(scenario);
    const std::string d = dat_name(scenario), c = colours[k++];
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
  for (const auto& [scenario, img] : r.figure6) {
    const std::string name = walk_scenario_name(scenario);
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
        walk_scenario_name(s.scenario), s.ms.median, s.ms.p95, s.ms.p99, 100 * s.within_10pct,
        s.mean_ssim, s.mean_ssim_objects, s.switches_per_frame);
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
    scenarios.push_back({{"name", walk_scenario_name(s.scenario)},
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
                       {{"policy", selection_policy_name(f.policy)},
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
  if (r.quality_context) j["quality_context"] = context_calibration_json(*r.quality_context);
  return j;
}

std::string table2_markdown(const HybridBenchResult& r) {
  std::ostringstream t;
  t << "| scenario | checkpoint | frame | SSIM | SSIM objects | PSNR dB | FLIP "
       "|\n|---|---|---|---|---|---|---|\n";
  for (const HybridScenarioResult& s : r.scenarios)
    for (const HybridCheckpoint& c : s.checkpoints)
      t << fmt::format("| {} | {} | {} | {:.4f} | {:.4f} | {:.2f} | {:.4f} |\n",
                       walk_scenario_name(s.scenario), c.name, c.frame, c.ssim, c.ssim_objects,
                       c.psnr, c.flip);
  return t.str();
}

void write_hybrid_report(const HybridBenchResult& r, OutputDir& out) {
  for (const HybridScenarioResult& s : r.scenarios) write_frames(s, out);
  write_text(out.file("plots.gp"), plots_script(r));
  const std::string plot_error = run_gnuplot(out.partial().string(), "plots.gp");
  const std::vector<std::string> fig6 = write_figure6(r, out);
  const std::string table2 = table2_markdown(r);
  write_text(out.file("table2.md"), table2);
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
          walk_scenario_name(s.scenario), c.name, c.frame, c.ssim, c.ssim_objects, c.psnr, c.flip);
  h << "</table>\n<h2>Figure 6: checkpoint " << r.figure6_checkpoint << "</h2>\n";
  for (const std::string& f : fig6)
    h << "<figure style='display:inline-block'><img src='" << f << "' width=420><figcaption>" << f
      << "</figcaption></figure>\n";
  h << "</body></html>\n";
  write_text(out.file("index.html"), h.str());
}

nlohmann::json context_calibration_json(const std::vector<ContextCalibration>& rows) {
  nlohmann::json j = nlohmann::json::array();
  for (const ContextCalibration& c : rows)
    j.push_back({{"model", c.model},
                 {"kind", object_kind_name(c.kind)},
                 {"level", c.level},
                 {"resolution", c.resolution},
                 {"error_scale", c.error_scale},
                 {"predicted", c.predicted},
                 {"measured", c.measured},
                 {"pixels", c.pixels}});
  return j;
}

nlohmann::json quality_diagnosis_json(const std::vector<DiagnosisRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const DiagnosisRow& d : rows) {
    nlohmann::json row = {{"condition", diagnosis_condition_name(d.condition)},
                          {"checkpoint", d.checkpoint},
                          {"bucket", d.bucket},
                          {"instances", d.instances},
                          {"covered_px", d.covered_px},
                          {"theta_deg", d.theta_deg},
                          {"size_px", d.size_px},
                          {"representation", d.representation},
                          {"predicted", d.predicted},
                          {"measured", d.measured},
                          {"ms", d.ms},
                          {"ms_full", d.ms_full}};
    if (d.predicted_context) row["predicted_context"] = *d.predicted_context;
    out.push_back(std::move(row));
  }
  return out;
}

nlohmann::json budget_sweep_json(const std::vector<BudgetSweepRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const BudgetSweepRow& b : rows) {
    nlohmann::json row = {{"checkpoint", b.checkpoint},
                          {"scenario", b.scenario},
                          {"fraction", b.fraction},
                          {"budget_ms", b.budget_ms},
                          {"predicted_ms", b.predicted_ms},
                          {"ms", b.ms},
                          {"full_ms", b.full_ms},
                          {"full_predicted_ms", b.full_predicted_ms},
                          {"terrain_ms", b.terrain_ms},
                          {"expected_ssim", b.expected_ssim},
                          {"ssim_objects", b.ssim_objects},
                          {"ssim", b.ssim},
                          {"triangles", b.triangles},
                          {"by_kind", b.by_kind}};
    if (b.cost_split) {
      nlohmann::json& split = row["cost_split"] = nlohmann::json::array();
      for (const CostSplitRow& k : *b.cost_split)
        split.push_back({{"kind", object_kind_name(k.kind)},
                         {"instances", k.instances},
                         {"draw_calls", k.draw_calls},
                         {"predicted_ms", k.predicted_ms},
                         {"alone_ms", k.alone_ms},
                         {"in_frame_ms", k.in_frame_ms}});
    }
    out.push_back(std::move(row));
  }
  return out;
}

std::string hybrid_summary_text(const HybridBenchResult& r) {
  const double target_ms = r.target_ms;
  std::string t;
  for (const HybridScenarioResult& s : r.scenarios)
    t += fmt::format(
        "{:14} median {:7.1f} ms  p95 {:7.1f} ms  p99 {:7.1f} ms  (target {:g} ms, {:.0f}% "
        "within +10%)  "
        "mean SSIM {:.4f}, objects {:.4f}, {:.2f} switches/frame\n",
        walk_scenario_name(s.scenario), s.ms.median, s.ms.p95, s.ms.p99, target_ms,
        100 * s.within_10pct, s.mean_ssim, s.mean_ssim_objects, s.switches_per_frame);
  t += fmt::format("full geometry's median over the run: {:.1f}x the target\n",
                   r.scenarios.front().ms.median / target_ms);
  const HybridScenarioResult* culled = r.scenario(WalkScenario::kFullCulled);
  if (culled)
    t += fmt::format(
        "occlusion culling: {:.0f} instances a frame behind the terrain (mean); full geometry "
        "without them: median {:.1f} ms ({:.1f}x the target), mean SSIM against full {:.4f}; "
        "depth read-back and pyramid {:.2f} ms a frame\n",
        culled->occluded_per_frame, culled->ms.median, culled->ms.median / target_ms,
        culled->mean_ssim, culled->occlusion_ms);
  const SelectionFigures& f = r.selection;
  t += fmt::format(
      "selection ({}): {:.3f} ms/frame median, p95 {:.3f}; of which the policy {:.3f}, p95 "
      "{:.3f}; viewing and pricing the instances {:.3f}, p95 {:.3f}{}; "
      "objective optimal {:.5f} vs greedy {:.5f} (mean gain {:.3f}%, max {:.3f}%)\n",
      selection_policy_name(f.policy), f.ms_per_frame, f.ms_p95, f.policy_ms_per_frame,
      f.policy_ms_p95, f.view_ms_per_frame, f.view_ms_p95, culled ? ", beside the read-back" : "",
      f.objective_optimal, f.objective_greedy, 100 * f.gain_mean, 100 * f.gain_max);
  return t;
}

nlohmann::json controller_replay_json(const ControllerReplayResult& r) {
  nlohmann::json series = nlohmann::json::array();
  for (const ReplaySeries& s : r.series)
    series.push_back({{"run", s.run},
                      {"scenario", walk_scenario_name(s.scenario)},
                      {"target_ms", s.target_ms},
                      {"frames", s.frames},
                      {"recorded_p95_over_target", s.recorded_p95_over_target},
                      {"replayed_p95_over_target", s.replayed_p95_over_target},
                      {"replayed_median_over_target", s.replayed_median_over_target},
                      {"replayed_budget_over_target", s.replayed_budget_over_target},
                      {"recorded_budget_ms", s.recorded_budget_ms},
                      {"replayed_budget_ms", s.replayed_budget_ms}});
  const BudgetControllerOptions& c = r.controller;
  return {{"controller",
           {{"tolerance", c.tolerance},
            {"quantile_margin", c.quantile_margin},
            {"prior_noise", c.prior_noise},
            {"drift", c.drift},
            {"centre_half_width", c.centre_half_width},
            {"quantile_window", c.quantile_window},
            {"quantile_min_frames", c.quantile_min_frames}}},
          {"series", series},
          {"recorded_within_10pct", r.recorded_within_10pct},
          {"replayed_within_10pct", r.replayed_within_10pct},
          {"replayed_p95_median", r.replayed_p95_median},
          {"replayed_budget_mean", r.replayed_budget_mean}};
}

std::string controller_replay_table(const ControllerReplayResult& r) {
  std::string t = fmt::format("{:<40} {:<14} {:>6} {:>13} {:>13} {:>10} {:>10}\n", "run",
                              "scenario", "target", "recorded p95", "replayed p95", "median",
                              "budget");
  for (const ReplaySeries& s : r.series)
    t += fmt::format("{:<40} {:<14} {:>6.1f} {:>12.3f}x {:>12.3f}x {:>9.3f}x {:>9.3f}x\n", s.run,
                     walk_scenario_name(s.scenario), s.target_ms, s.recorded_p95_over_target,
                     s.replayed_p95_over_target, s.replayed_median_over_target,
                     s.replayed_budget_over_target);
  t += fmt::format(
      "{} series: p95 within +10% recorded {:.0f}%, replayed {:.0f}%; replayed p95 median "
      "{:.3f}x, mean budget {:.3f}x target\n",
      r.series.size(), 100 * r.recorded_within_10pct, 100 * r.replayed_within_10pct,
      r.replayed_p95_median, r.replayed_budget_mean);
  return t;
}

}  // namespace terrasprite::report
