// SPDX-License-Identifier: MIT
// The budget controller replayed on recorded walkthroughs: their frames
// files read, each series replayed, the figures over all series.
#include "terrasprite/experiment/hybrid/controller_replay_run.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "terrasprite/common/error.h"
#include "terrasprite/common/input_file.h"
#include "terrasprite/common/stats.h"

namespace terrasprite {
namespace {

/// The header's column names by position. Throws InputError naming `file`
/// unless ms, predicted_ms and budget_ms are among them.
std::map<std::string, std::size_t> frame_columns(const std::string& line, const std::string& file) {
  std::map<std::string, std::size_t> column;
  std::istringstream h(line);
  std::string name;
  for (std::size_t i = 0; h >> name; ++i) column[name] = i;
  for (const char* k : {"ms", "predicted_ms", "budget_ms"})
    if (!column.count(k))
      throw InputError(fmt::format("{}: no '{}' column (not a bench hybrid frames file)", file, k));
  return column;
}

/// A row's fields as numbers ("NaN" included). Throws InputError naming
/// `file` and the line for a field that is not a number.
std::vector<double> frame_row(const std::string& line, const std::string& file, int row) {
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
  return v;
}

/// The frame of a row. A drawn frame's time is a finite positive number; its
/// prediction and budget are NaN on frames drawn without a selection, and
/// finite and non-negative otherwise.
RecordedFrame recorded_frame(const std::vector<double>& v,
                             const std::map<std::string, std::size_t>& column,
                             const std::string& file, int row) {
  const RecordedFrame f{v[column.at("ms")], v[column.at("predicted_ms")],
                        v[column.at("budget_ms")]};
  if (!std::isfinite(f.ms) || f.ms <= 0)
    throw InputError(fmt::format("{}: line {}: ms {}: a frame time must be finite and positive",
                                 file, row, f.ms));
  for (const auto& [name, x] :
       {std::pair{"predicted_ms", f.predicted_ms}, {"budget_ms", f.budget_ms}})
    if (!std::isnan(x) && !(std::isfinite(x) && x >= 0))
      throw InputError(fmt::format("{}: line {}: {} {}: must be finite and non-negative, or NaN",
                                   file, row, name, x));
  return f;
}

/// Fraction of `v` at or under 1.1 (a p95 within +10% of the target).
double within_10pct(const std::vector<double>& v) {
  int n = 0;
  for (double x : v) n += x <= 1.1;
  return double(n) / double(v.size());
}

/// One scenario of one run replayed under `controller` at `target_ms`.
ReplaySeries replay_series(const std::string& run, WalkScenario scenario, double target_ms,
                           const BudgetControllerOptions& controller) {
  const std::string file = (std::filesystem::path(run) /
                            (std::string("frames_") + walk_scenario_name(scenario) + ".dat"))
                               .string();
  const std::vector<RecordedFrame> frames = read_recorded_frames(file);
  std::vector<double> ms;
  ReplaySeries s{run, scenario, target_ms};
  for (const RecordedFrame& f : frames) {
    ms.push_back(f.ms);
    s.recorded_budget_ms.push_back(f.budget_ms);
  }
  BudgetControllerOptions o = controller;
  o.target_ms = target_ms;
  const ReplayResult r = replay_controller(frames, o);
  if (r.ms.empty()) throw InputError(fmt::format("{}: no frame with a time and prediction", file));
  s.frames = r.ms.size();
  s.recorded_p95_over_target = summarize(ms).p95 / target_ms;
  s.replayed_p95_over_target = r.p95_ms / target_ms;
  s.replayed_median_over_target = r.median_ms / target_ms;
  s.replayed_budget_over_target = r.mean_budget_ms / target_ms;
  s.replayed_budget_ms = r.budget_ms;
  return s;
}

}  // namespace

std::vector<RecordedFrame> read_recorded_frames(const std::string& file) {
  std::istringstream in(read_input_text(file, "frames file"));
  std::string line;
  if (!std::getline(in, line)) throw InputError(fmt::format("{}: empty, no header", file));
  const std::map<std::string, std::size_t> column = frame_columns(line, file);
  std::vector<RecordedFrame> out;
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const std::vector<double> v = frame_row(line, file, row);
    if (v.size() != column.size())
      throw InputError(fmt::format("{}: line {}: {} fields, the header names {}", file, row,
                                   v.size(), column.size()));
    out.push_back(recorded_frame(v, column, file, row));
  }
  return out;
}

double recorded_target_ms(const std::string& run_dir) {
  const std::string file = (std::filesystem::path(run_dir) / "hybrid.json").string();
  const nlohmann::json j = nlohmann::json::parse(read_input_text(file, "bench hybrid result"),
                                                 nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw InputError(fmt::format("{}: not JSON", file));
  if (!j.is_object() || !j.contains("target_ms") || !j["target_ms"].is_number() ||
      !(j["target_ms"] > 0) || !std::isfinite(j["target_ms"].get<double>()))
    throw InputError(fmt::format("{}: no positive target_ms", file));
  return j["target_ms"].get<double>();
}

ControllerReplayResult run_controller_replay(const ControllerReplayOptions& o) {
  if (o.runs.empty()) throw InputError("replay-controller: name at least one run directory");
  ControllerReplayResult result;
  result.controller = o.controller;
  std::vector<double> recorded_p95, replayed_p95, budget;
  for (const std::string& run : o.runs) {
    const double target = recorded_target_ms(run);
    for (WalkScenario s : o.scenarios) {
      result.series.push_back(replay_series(run, s, target, o.controller));
      const ReplaySeries& r = result.series.back();
      recorded_p95.push_back(r.recorded_p95_over_target);
      replayed_p95.push_back(r.replayed_p95_over_target);
      budget.push_back(r.replayed_budget_over_target);
    }
  }
  result.recorded_within_10pct = within_10pct(recorded_p95);
  result.replayed_within_10pct = within_10pct(replayed_p95);
  result.replayed_p95_median = median(replayed_p95);
  result.replayed_budget_mean = mean(budget);
  return result;
}

}  // namespace terrasprite
