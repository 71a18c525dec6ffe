// SPDX-License-Identifier: MIT
// `bench hybrid`: the walkthrough's typed results, and the report written
// from them (JSON, the paper's Figures 4-6 and Table 2, index.html), and
// the walkthrough's scoring.
#pragma once
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/common/image.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/hybrid/hybrid_objects.h"
#include "terrasprite/hybrid/walkthrough_path.h"
#include "terrasprite/objects/gl_scene_objects.h"
#include "terrasprite/objects/quality_table.h"
#include "terrasprite/output/output_dir.h"

namespace terrasprite::cli {

struct HybridCheckpoint {
  std::string name;
  int frame = 0;
  double ssim = 1, ssim_objects = 1, psnr = kPsnrCapDb, flip = 0;
};

struct HybridScenarioResult {
  std::string name;
  Summary ms;               ///< frame time, terrain included
  double within_10pct = 0;  ///< fraction of frames at or under target + 10%
  double mean_ssim = 1, mean_ssim_objects = 1;
  double switches_per_frame = 0;
  /// Means over frames: instances in the frustum but behind the terrain, left
  /// out before selection (0 where the scenario does not cull), and the time
  /// of the depth read-back and pyramid that found them.
  double occluded_per_frame = 0, occlusion_ms = 0;
  std::vector<HybridCheckpoint> checkpoints;
  std::vector<FrameResult> frames;
};

struct SelectionFigures {
  std::string policy = "optimal";
  double ms_per_frame = 0, ms_p95 = 0;  ///< selection (view, options, policy, hysteresis)
  /// Of which the policy (the knapsack) and the hysteresis: the issue's
  /// "under 1 ms" is the knapsack's; viewing 400 instances is apart.
  double policy_ms_per_frame = 0, policy_ms_p95 = 0;
  /// Viewing and pricing the instances, on whichever thread ran it (beside
  /// the occlusion read-back: then not in ms_per_frame).
  double view_ms_per_frame = 0, view_ms_p95 = 0;
  double objective_greedy = 0, objective_optimal = 0;  ///< means over the same frames
  double gain_mean = 0, gain_max = 0;  ///< relative gain of optimal over greedy per frame
  int frames = 0;
};

struct HybridBenchResult {
  std::string gl_renderer;
  /// LP_NUM_THREADS as the run had it (apply_llvmpipe_threads), or nullopt: unset.
  std::optional<std::string> llvmpipe_threads;
  int msaa = 1;  ///< samples a pixel of every image drawn (--msaa)
  double target_ms = 0;
  int width = 0, height = 0;
  int frames = 0, instances = 0, score_every = 1;
  double terrain_ms = 0;        ///< terrain alone, median
  double full_ms_at_start = 0;  ///< full geometry on six path frames, median
  bool target_auto = false;     ///< target_ms = full_ms_at_start / --full-over-target
  /// The cost calibration's measured / predicted table (calibration_report).
  std::string calibration;
  /// The tables in context (calibrate_tables_in_context's report), or null.
  nlohmann::json quality_context;
  long long full_triangles_max = 0;
  std::vector<HybridScenarioResult> scenarios;  ///< full first
  SelectionFigures selection;
  std::string figure6_checkpoint;
  /// Figure 6: the images at that checkpoint, full first, by scenario.
  std::vector<std::pair<std::string, Image>> figure6;
};

/// Per-frame state the scorer shares with the frame callback: which frame
/// this is, and where the terrain alone is (object pixels are those in front
/// of it in either image).
struct ScoringState {
  int frame = -1;
  std::vector<float> terrain_depth;
  std::vector<int> flip_frames;
};

/// Pixels where either depth image has something in front of the terrain
/// alone (`terrain`, the same size; linear depth, +inf where nothing was
/// drawn): the objects' pixels, on which `ssim_objects` is measured.
std::vector<std::uint8_t> object_mask(const std::vector<float>& ref_depth,
                                      const std::vector<float>& test_depth,
                                      const std::vector<float>& terrain);
/// Whole-frame SSIM, PSNR and FLIP (FLIP only on `state`'s flip frames)
/// and `ssim_objects` over object_mask (hybrid_scoring.cpp). `state` is
/// updated by the run's frame callback before each frame is scored.
Scorer hybrid_scorer(std::shared_ptr<ScoringState> state);

/// A frame's selection figures (objects.last()) as `r`'s counters, the
/// names the .dat files, summarise and selection_figures read.
void annotate_frame(const HybridObjects& objects, FrameResult& r);

/// One scenario's run summarised (frame time against `target_ms`, quality
/// at `checkpoints`: a checkpoint not scored keeps SSIM 1) (hybrid_summary.cpp).
HybridScenarioResult summarise(const RendererRun& run, double target_ms,
                               const std::vector<PathCheckpoint>& checkpoints);
/// The selection's time per frame and the optimal policy's objective against
/// greedy's over the frames that carry both (counters of `run`).
SelectionFigures selection_figures(const RendererRun& run);

nlohmann::json hybrid_json(const HybridBenchResult& r);
/// Writes the .dat files, figures (gnuplot; a failure is a note), the Figure
/// 6 images and index.html into `out`.
void write_hybrid_report(const HybridBenchResult& r, OutputDir& out);
/// Table 2 as Markdown (also printed by the command).
std::string table2_markdown(const HybridBenchResult& r);

/// What --quality-diagnosis needs from the bench's setup.
struct QualityDiagnosisInput {
  GlSceneObjects& set;
  const std::vector<QualityTable>& tables;
  Scene& ground;
  const std::vector<Camera>& path;
  const std::vector<PathCheckpoint>& checkpoints;
  int width = 0, height = 0, terrain_quads = 64;
  /// scene (over the terrain), sky (over the clear colour, as the tables),
  /// scene4 (over the terrain at 4 x the image size).
  std::vector<std::string> conditions;
  std::string image_dir;  ///< when set: every image of the 'all' group, as PNG
  /// The tables in context (calibrate_tables_in_context), when measured:
  /// their prediction is reported next to the raw tables'.
  const std::vector<QualityTable>* context_tables = nullptr;
  int samples = 1;  ///< a pixel's, as the walkthrough draws (RasterOptions::samples)
};
/// Per checkpoint, on-screen size bucket and representation: the tables'
/// predicted SSIM against the one measured (hybrid_quality_diagnosis.cpp).
nlohmann::json diagnose_hybrid_quality(const QualityDiagnosisInput& in);

/// What calibrate_tables_in_context needs.
struct QualityContextInput {
  GlSceneObjects& set;
  Scene& ground;
  std::vector<Camera> cameras;  ///< walkthrough views (not the checkpoints')
  int width = 0, height = 0, terrain_quads = 64;
  double max_impostor_size_px = 0;  ///< as HybridOptions: impostors not offered past it
  int samples = 1;                  ///< a pixel's, as the walkthrough draws
};
/// The tables in context: at each camera, each model's visible instances are
/// drawn over the terrain at full geometry and at each representation of
/// its table, scored as the bench scores; each representation's SSIM
/// samples are rescaled by the fitted error scale (quality_calibration.h).
/// Returns per (model, representation): error_scale, predicted, measured.
nlohmann::json calibrate_tables_in_context(const QualityContextInput& in,
                                           std::vector<QualityTable>& tables);

/// The paper's full geometry, the walkthrough's reference: every instance
/// in the frustum at level 0, nothing culled behind the terrain (bench_hybrid.cpp).
HybridScenario full_geometry_scenario();

/// What quality_budget_sweep needs.
struct BudgetSweepInput {
  GlSceneObjects& set;
  const std::vector<QualityTable>& tables;
  const DrawCostModel& cost;
  Scene& ground;
  const std::vector<Camera>& path;
  const std::vector<PathCheckpoint>& checkpoints;
  int width = 0, height = 0, terrain_quads = 64;
  HybridOptions options;
  std::vector<HybridScenario> scenarios;  ///< drawn at each budget (control set to kFixed)
  std::vector<double> fractions;          ///< budgets: these fractions of full's predicted frame
  /// When set (the tables as measured, `tables` being in context): every
  /// scenario also selects from these, named "<name> (tables as measured)".
  const std::vector<QualityTable>* raw_tables = nullptr;
  /// Above 0: each row also times its frame split by kind (`cost_split`:
  /// per kind drawn, `predicted_ms`, `alone_ms`, `in_frame_ms`), over this
  /// many interleaved rounds of redraws.
  int cost_split_rounds = 0;
  int samples = 1;  ///< a pixel's, as the walkthrough draws
};
/// Quality against budget, without the controller: at each checkpoint each
/// scenario selects once under a fixed budget (a fraction of full
/// geometry's predicted frame time) and is scored against full geometry
/// (object-masked and whole-frame SSIM) and timed (median of 3).
nlohmann::json quality_budget_sweep(const BudgetSweepInput& in);

}  // namespace terrasprite::cli
