// SPDX-License-Identifier: MIT
// terrasprite bench replay-controller: the budget controller replayed on the
// frames of recorded `bench hybrid` runs (their frames_<scenario>.dat), with
// its options changed, to judge a change to the loop on this machine's real
// noise in seconds instead of flying the walkthrough again.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "bench_commands.h"
#include "cli_common.h"
#include "terrasprite/hybrid/controller_replay.h"
#include "terrasprite/common/error.h"
#include "terrasprite/common/stats.h"

namespace terrasprite::cli {
namespace {

struct ReplayArgs {
  std::vector<std::string> runs;
  std::string scenarios = "pm,mixed-optimal", json;
  BudgetControllerOptions controller;
};

/// The recorded frames of one scenario of one run: ms, predicted_ms and
/// budget_ms by their header names. Throws InputError naming the file.
std::vector<RecordedFrame> read_frames(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot read the file", file));
  std::string line;
  if (!std::getline(in, line)) throw InputError(fmt::format("{}: empty, no header", file));
  std::map<std::string, std::size_t> column;
  {
    std::istringstream h(line);
    std::string name;
    for (std::size_t i = 0; h >> name; ++i) column[name] = i;
  }
  for (const char* k : {"ms", "predicted_ms", "budget_ms"})
    if (!column.count(k))
      throw InputError(fmt::format("{}: no '{}' column (not a bench hybrid frames file)", file, k));
  std::vector<RecordedFrame> out;
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    std::istringstream r(line);
    std::vector<double> v;
    for (std::string field; r >> field;) {
      std::size_t used = 0;
      double x = NAN;
      try {
        x = std::stod(field, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != field.size())
        throw InputError(fmt::format("{}: line {}: '{}' is not a number", file, row, field));
      v.push_back(x);
    }
    if (v.size() != column.size())
      throw InputError(fmt::format("{}: line {}: {} fields, the header names {}", file, row,
                                   v.size(), column.size()));
    out.push_back({v[column["ms"]], v[column["predicted_ms"]], v[column["budget_ms"]]});
  }
  return out;
}

double target_of(const std::string& run) {
  const std::string file = (std::filesystem::path(run) / "hybrid.json").string();
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot read the file (a bench hybrid --out?)", file));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{}: not JSON ({})", file, e.what()));
  }
  if (!j.contains("target_ms") || !j["target_ms"].is_number() || !(j["target_ms"] > 0))
    throw InputError(fmt::format("{}: no positive target_ms", file));
  return j["target_ms"].get<double>();
}

void run_replay(const ReplayArgs& a) {
  if (a.runs.empty()) throw InputError("replay-controller: name at least one run directory");
  if (!a.json.empty()) check_outputs("", {a.json});
  const std::vector<std::string> scenarios = split_list(a.scenarios);
  nlohmann::json series = nlohmann::json::array();
  std::vector<double> recorded_p95, replayed_p95, budget;
  fmt::print("{:<40} {:<14} {:>6} {:>13} {:>13} {:>10} {:>10}\n", "run", "scenario", "target",
             "recorded p95", "replayed p95", "median", "budget");
  for (const std::string& run : a.runs) {
    const double target = target_of(run);
    for (const std::string& s : scenarios) {
      const std::string file = (std::filesystem::path(run) / ("frames_" + s + ".dat")).string();
      const std::vector<RecordedFrame> frames = read_frames(file);
      std::vector<double> ms, recorded_budget;
      for (const RecordedFrame& f : frames) {
        ms.push_back(f.ms);
        recorded_budget.push_back(f.budget_ms);
      }
      BudgetControllerOptions o = a.controller;
      o.target_ms = target;
      const ReplayResult r = replay_controller(frames, o);
      if (r.ms.empty())
        throw InputError(fmt::format("{}: no frame with a time and prediction", file));
      const double rec = summarize(ms).p95 / target, rep = r.p95_ms / target;
      recorded_p95.push_back(rec);
      replayed_p95.push_back(rep);
      budget.push_back(r.mean_budget_ms / target);
      fmt::print("{:<40} {:<14} {:>6.1f} {:>12.3f}x {:>12.3f}x {:>9.3f}x {:>9.3f}x\n", run, s,
                 target, rec, rep, r.median_ms / target, r.mean_budget_ms / target);
      series.push_back({{"run", run},
                        {"scenario", s},
                        {"target_ms", target},
                        {"frames", r.ms.size()},
                        {"recorded_p95_over_target", rec},
                        {"replayed_p95_over_target", rep},
                        {"replayed_median_over_target", r.median_ms / target},
                        {"replayed_budget_over_target", r.mean_budget_ms / target},
                        // Per frame, to show where a dip falls (a mean hides it).
                        {"recorded_budget_ms", recorded_budget},
                        {"replayed_budget_ms", r.budget_ms}});
    }
  }
  auto within = [](const std::vector<double>& v) {
    int n = 0;
    for (double x : v) n += x <= 1.1;
    return double(n) / double(v.size());
  };
  fmt::print(
      "{} series: p95 within +10% recorded {:.0f}%, replayed {:.0f}%; replayed p95 median "
      "{:.3f}x, mean budget {:.3f}x target\n",
      series.size(), 100 * within(recorded_p95), 100 * within(replayed_p95), median(replayed_p95),
      mean(budget));
  if (!a.json.empty())
    write_json({{"controller",
                 {{"tolerance", a.controller.tolerance},
                  {"quantile_margin", a.controller.quantile_margin},
                  {"prior_noise", a.controller.prior_noise},
                  {"drift", a.controller.drift},
                  {"centre_half_width", a.controller.centre_half_width},
                  {"quantile_window", a.controller.quantile_window},
                  {"quantile_min_frames", a.controller.quantile_min_frames}}},
                {"series", series},
                {"recorded_within_10pct", within(recorded_p95)},
                {"replayed_within_10pct", within(replayed_p95)},
                {"replayed_p95_median", median(replayed_p95)},
                {"replayed_budget_mean", mean(budget)}},
               a.json);
}

}  // namespace

void add_bench_replay_controller(CLI::App& bench) {
  auto* cmd = bench.add_subcommand(
      "replay-controller",
      "the budget controller replayed on recorded bench hybrid runs (their frames_*.dat), with "
      "its options changed: p95 and budget against the target, recorded and replayed");
  auto a = std::make_shared<ReplayArgs>();
  cmd->add_option("runs", a->runs, "bench hybrid output directories (hybrid.json, frames_*.dat)")
      ->required();
  cmd->add_option("--scenarios", a->scenarios, "which scenarios' frames")->capture_default_str();
  cmd->add_option("--tolerance", a->controller.tolerance, "the p95's aim, x target")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 2.0));
  cmd->add_option("--margin", a->controller.quantile_margin,
                  "standard errors of the sample p95 added to it")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--centre-half-width", a->controller.centre_half_width,
                  "frames each side of the running median the spread is taken about")
      ->capture_default_str()
      ->check(CLI::Range(1, 50));
  cmd->add_option("--prior-noise", a->controller.prior_noise,
                  "frame noise (sigma, log) assumed until three frames are in")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 2.0));
  cmd->add_option("--quantile-window", a->controller.quantile_window, "frames in the p95's window")
      ->capture_default_str()
      ->check(CLI::Range(4, 10000));
  cmd->add_option("--quantile-min-frames", a->controller.quantile_min_frames,
                  "frames of spread in before the p95 window sets the aim (at most the window)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--drift", a->controller.drift,
                  "how far the measured / predicted ratio is taken to move per frame (sigma, "
                  "log): sets how fast the ratio follows the frames")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--json", a->json, "also write the figures as JSON");
  cmd->callback([a] { run_replay(*a); });
}

}  // namespace terrasprite::cli
