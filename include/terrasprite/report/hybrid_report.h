// SPDX-License-Identifier: MIT
// The hybrid walkthrough's report from its typed result: JSON, the per-frame
// .dat files, the paper's Figure 4 (frame time), Figure 5 (triangles),
// Table 2 (quality at the checkpoints), Figure 6 (images at one checkpoint,
// with differences) and index.html; and the controller replay's JSON and table.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "terrasprite/experiment/hybrid/controller_replay_run.h"
#include "terrasprite/experiment/hybrid/hybrid.h"
#include "terrasprite/output/output_dir.h"

namespace terrasprite::report {

/// The walkthrough's JSON document (hybrid.json).
nlohmann::json hybrid_json(const HybridBenchResult& r);
/// The tables in context as JSON rows (model, kind, level, resolution,
/// error_scale, predicted, measured, pixels).
nlohmann::json context_calibration_json(const std::vector<ContextCalibration>& rows);
/// The quality diagnosis's rows as a JSON array (`--quality-diagnosis`).
nlohmann::json quality_diagnosis_json(const std::vector<DiagnosisRow>& rows);
/// The budget sweep's rows as a JSON array (`--budget-sweep`); a row's
/// `cost_split` is there when it was measured.
nlohmann::json budget_sweep_json(const std::vector<BudgetSweepRow>& rows);
/// Writes frames_<scenario>.dat per scenario, plots.gp and its figures
/// (gnuplot; a failure is a note in index.html), the Figure 6 images,
/// table2.md and index.html into `out`. Throws InputError naming a file
/// that cannot be written.
void write_hybrid_report(const HybridBenchResult& r, OutputDir& out);
/// Table 2 as Markdown (also printed by the command).
std::string table2_markdown(const HybridBenchResult& r);
/// The walkthrough's figures in lines of text: one per scenario, full
/// geometry against the target, the occlusion culling's (when the run
/// culled) and the selection's.
std::string hybrid_summary_text(const HybridBenchResult& r);

/// The replay's JSON document (the controller's options, every series,
/// the figures over them).
nlohmann::json controller_replay_json(const ControllerReplayResult& r);
/// The replay as a text table, a row per series, and a closing line.
std::string controller_replay_table(const ControllerReplayResult& r);

}  // namespace terrasprite::report
