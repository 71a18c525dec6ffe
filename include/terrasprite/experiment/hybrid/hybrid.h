// SPDX-License-Identifier: MIT
// The hybrid-objects walkthrough of Jehaes, Lamotte & Tack (GRAPP 2008,
// section 4): the object scene flown along a path with several selection
// scenarios interleaved frame by frame (full geometry as the reference,
// relief impostors only, LOD meshes only, the paper's mixed policy, optimal
// selection over every representation), each scored against full geometry.
// Also its two side studies: quality against fixed budgets and the tables'
// predicted quality against the measured one. Typed options in, typed
// results out; report/hybrid_report.h writes them.
// The defaults' figures: docs/results/2026-12-07-hybrid-defaults.md
#pragma once
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "terrasprite/common/image.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/hybrid/budget_controller.h"
#include "terrasprite/hybrid/frame_pace.h"
#include "terrasprite/hybrid/hybrid_objects.h"
#include "terrasprite/objects/gl_scene_objects.h"
#include "terrasprite/objects/quality_table.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

/// The walkthrough's scenarios, in the order they are run and reported.
enum class WalkScenario {
  kFull,          ///< every instance in the frustum at full geometry: the reference
  kIbr,           ///< relief impostors only, unbudgeted
  kPm,            ///< LOD meshes only, greedy under the PI budget
  kMixed,         ///< the paper's mixed policy with its quality-step controller
  kMixedOptimal,  ///< optimal selection over meshes, relief and octahedral
  kFullCulled,    ///< full geometry less what the terrain hides (with occlusion culling only)
};
/// "full", "ibr", "pm", "mixed", "mixed-optimal", "full-culled": the names
/// of the report's scenarios and of its frames_<name>.dat files.
const char* walk_scenario_name(WalkScenario s);
/// The scenario of that name, or nullopt for any other text.
std::optional<WalkScenario> parse_walk_scenario(std::string_view name);
/// The scenarios a walkthrough runs: full first; full-culled last, with
/// `occlusion_cull` only.
std::vector<WalkScenario> walk_scenarios(bool occlusion_cull);
/// The selection setup of `s`. With `occlusion_cull` every scenario but
/// `full` leaves out what is behind the terrain (DepthOcclusion).
HybridScenario walk_scenario(WalkScenario s, bool occlusion_cull);

/// Where the quality diagnosis draws each group of instances.
enum class DiagnosisCondition {
  kScene,   ///< over the terrain, as the walkthrough draws
  kSky,     ///< over the clear colour, as the quality tables are measured
  kScene4,  ///< over the terrain at 4 x the image size
};
/// "scene", "sky", "scene4".
const char* diagnosis_condition_name(DiagnosisCondition c);
std::optional<DiagnosisCondition> parse_diagnosis_condition(std::string_view name);

/// What run_hybrid measures.
enum class HybridMode {
  kWalkthrough,       ///< the scenarios along the path (HybridBenchResult's walkthrough figures)
  kQualityDiagnosis,  ///< per checkpoint, size bucket and representation: predicted vs measured SSIM
  kBudgetSweep,       ///< pm and mixed-optimal under fixed budgets at each checkpoint
};

/// `bench hybrid`'s options. Sizes in pixels, times in milliseconds, angles
/// in degrees. The CLI checks every value before any work; run_hybrid
/// assumes them in range (noted per field).
struct HybridBenchOptions {
  HybridMode mode = HybridMode::kWalkthrough;
  std::string scene_file;                   ///< object scene (JSON); empty: the built-in scene
  std::string models_dir = "../shared/data";  ///< where the built-in scene's models are
  std::string path_file;                    ///< path JSON with checkpoints; empty: the walkthrough
  std::string cache_dir;                    ///< representations; empty: default_cache_dir()
  int width = 320, height = 180;            ///< image size, > 0
  /// The frame-time target; nullopt: auto, full geometry's time timed before
  /// the walk over `full_over_target`, rounded down to 0.1 ms.
  std::optional<double> target_ms;
  double full_over_target = 5.3;  ///< >= 1
  int frames = 160;               ///< along the path, >= 2
  int score_every = 2;            ///< full geometry drawn and scored every n-th frame, >= 1
  int instances = 0;              ///< keep this many, drawn at random (seeded); 0: all
  int terrain_quads = 64;         ///< coarse terrain mesh quads per side (the objects stand on it)
  /// Budgeted scenarios may leave instances under this on-screen diameter
  /// undrawn when the budget cannot draw every one at its cheapest (0: never).
  double cull_px = 4;
  double quality_spread_penalty = 0;  ///< HybridOptions::quality_spread_penalty
  bool occlusion_cull = true;         ///< leave out what the terrain hides; adds full-culled
  double p95_margin = BudgetControllerOptions{}.quantile_margin;
  double p95_aim = BudgetControllerOptions{}.tolerance;
  double pace_max_slope = FramePaceOptions{}.max_slope;
  /// Quality-table sampling: on-screen sizes (kMinTableSizePx..kMaxTableSizePx),
  /// impostor resolutions (16..512), view step and model headings ([0, 360)).
  std::vector<int> table_sizes{200, 50, 16, 8, 4};
  std::vector<int> relief_resolutions{32, 64, 128, 256};
  std::vector<int> octahedral_resolutions{32, 64, 128};
  double table_angle_step = 45;
  std::vector<double> table_headings{0, 45, 90, 135, 180, 225, 270, 315};
  bool table_full_sphere = true;
  std::string figure6 = "C";  ///< the checkpoint Figure 6 shows (none when no checkpoint has it)
  /// Cost calibration sizes (4..8192); empty: image height / 8, / 2 and x 2.
  std::vector<int> calibration_sizes;
  int quality_context_frames = 0;  ///< rescale the tables to this many in-scene views (0: not)
  /// kBudgetSweep: the budgets, fractions in (0, 4] of full geometry's predicted frame.
  std::vector<double> budget_fractions{0.05, 0.1, 0.15, 0.2, 0.3, 0.5};
  int cost_split = 0;  ///< kBudgetSweep: rounds of per-kind cost split (0: none)
  std::vector<DiagnosisCondition> diagnosis_conditions{DiagnosisCondition::kScene,
                                                       DiagnosisCondition::kSky};
  std::string diagnosis_images;  ///< kQualityDiagnosis: existing folder for its images; empty: none
  int msaa = 4;                  ///< samples a pixel of every image drawn, 1..GL_MAX_SAMPLES
  /// LP_NUM_THREADS as the caller set it before the run (nullopt: unset);
  /// recorded in the result.
  std::optional<std::string> llvmpipe_threads;
};

/// Model `model`'s quality table for one sampling, measured or read from a
/// cache. Called with the run's GL context current.
using TableSource = std::function<QualityTable(GlSceneObjects& set, std::size_t model,
                                               const TableOptions& options)>;

/// The table samplings `o` asks for: meshes and relief, then octahedral.
std::vector<TableOptions> hybrid_table_options(const HybridBenchOptions& o);

/// What run_hybrid needs beside its options.
struct HybridBenchInputs {
  const Terrain& terrain;
  /// Where the tables come from; empty: measured now (no cache).
  TableSource tables;
  std::function<void(int done, int total)> progress;  ///< the walkthrough's; may be empty
};

struct HybridCheckpoint {
  std::string name;
  int frame = 0;
  double ssim = 1, ssim_objects = 1, psnr = kPsnrCapDb, flip = 0;
};

/// One scenario's frame: the driver's figures, the selection's figures
/// (absent where the frame was not annotated) and the object-masked SSIM
/// (absent where the frame was not scored).
struct HybridFrame {
  FrameResult drawn;
  std::optional<HybridFrameStats> selection;
  std::optional<double> ssim_objects;
};

struct HybridScenarioResult {
  WalkScenario scenario = WalkScenario::kFull;
  Summary ms;               ///< frame time, terrain included
  double within_10pct = 0;  ///< fraction of frames at or under target + 10%
  double mean_ssim = 1, mean_ssim_objects = 1;
  double switches_per_frame = 0;
  /// Means over frames: instances in the frustum but behind the terrain, left
  /// out before selection (0 where the scenario does not cull), and the time
  /// of the depth read-back and pyramid that found them.
  double occluded_per_frame = 0, occlusion_ms = 0;
  std::vector<HybridCheckpoint> checkpoints;
  std::vector<HybridFrame> frames;
};

/// The optimal policy's selection figures over a run.
struct SelectionFigures {
  SelectionPolicy policy = SelectionPolicy::kOptimal;
  double ms_per_frame = 0, ms_p95 = 0;  ///< selection (view, options, policy, hysteresis)
  /// Of which the policy (the knapsack) and the hysteresis.
  double policy_ms_per_frame = 0, policy_ms_p95 = 0;
  /// Viewing and pricing the instances, on whichever thread ran it (beside
  /// the occlusion read-back: then not in ms_per_frame).
  double view_ms_per_frame = 0, view_ms_p95 = 0;
  double objective_greedy = 0, objective_optimal = 0;  ///< means over the same frames
  double gain_mean = 0, gain_max = 0;  ///< relative gain of optimal over greedy per frame
  int frames = 0;
};

/// A representation's quality in context (calibrate_tables_in_context).
struct ContextCalibration {
  std::string model;
  ObjectKind kind = ObjectKind::kMesh;
  int level = 0, resolution = 0;
  double error_scale = 1;        ///< fitted factor on the table's 1 - SSIM
  double predicted = 1, measured = 1;  ///< pixel-weighted mean SSIM over the views
  double pixels = 0;                   ///< pixels the observations covered
};

/// A row of the quality diagnosis (HybridMode::kQualityDiagnosis): one
/// on-screen size group of instances at one checkpoint, drawn with one
/// uniform representation, against full geometry.
struct DiagnosisRow {
  DiagnosisCondition condition = DiagnosisCondition::kScene;
  std::string checkpoint;
  std::string bucket;          ///< the size group ("all", or a size range)
  std::size_t instances = 0;
  std::size_t covered_px = 0;  ///< pixels of the object mask
  double theta_deg = 0, size_px = 0;  ///< pixel-weighted means over the group
  std::string representation;         ///< the uniform representation's label
  double predicted = 1, measured = 1; ///< the tables' SSIM and the measured one
  std::optional<double> predicted_context;  ///< the tables in context, when measured
  double ms = 0, ms_full = 0;               ///< the frame, and full geometry's
};

/// One kind of representation in a swept frame, timed (the budget sweep's
/// cost split): alone over the terrain and as its share of the whole frame.
struct CostSplitRow {
  ObjectKind kind = ObjectKind::kMesh;
  int instances = 0, draw_calls = 0;
  double predicted_ms = 0, alone_ms = 0, in_frame_ms = 0;
};

/// A row of the budget sweep (HybridMode::kBudgetSweep): one scenario at one
/// checkpoint under a fixed budget, a fraction of full geometry's predicted
/// frame time.
struct BudgetSweepRow {
  std::string checkpoint, scenario;
  double fraction = 0, budget_ms = 0, predicted_ms = 0;
  double ms = 0, full_ms = 0, full_predicted_ms = 0, terrain_ms = 0;
  double expected_ssim = 1, ssim_objects = 1, ssim = 1;
  long long triangles = 0;
  std::array<int, 3> by_kind{};  ///< drawn instances by ObjectKind
  std::optional<std::vector<CostSplitRow>> cost_split;  ///< with HybridBenchOptions::cost_split
};

struct HybridBenchResult {
  HybridMode mode = HybridMode::kWalkthrough;
  std::string gl_renderer;
  std::optional<std::string> llvmpipe_threads;  ///< as HybridBenchOptions::llvmpipe_threads
  int msaa = 1;
  double target_ms = 0;
  int width = 0, height = 0;
  int frames = 0, instances = 0, score_every = 1;
  double terrain_ms = 0;        ///< terrain alone, median
  double full_ms_at_start = 0;  ///< full geometry on the scored frames, before the walk
  bool target_auto = false;     ///< target_ms = full_ms_at_start / full_over_target
  double full_over_target = 0;  ///< as the options (for the auto target's note)
  std::string calibration;      ///< the cost calibration's measured / predicted table
  /// The tables in context (quality_context_frames > 0), else nullopt.
  std::optional<std::vector<ContextCalibration>> quality_context;
  long long full_triangles_max = 0;
  std::vector<HybridScenarioResult> scenarios;  ///< walk_scenarios' order, full first
  SelectionFigures selection;
  std::string figure6_checkpoint;  ///< empty when no checkpoint has HybridBenchOptions::figure6
  /// Figure 6: the images at that checkpoint, full first, by scenario.
  std::vector<std::pair<WalkScenario, Image>> figure6;
  std::vector<DiagnosisRow> quality_diagnosis;  ///< kQualityDiagnosis's rows
  std::vector<BudgetSweepRow> budget_sweep;     ///< kBudgetSweep's rows

  /// The scenario `s`'s result, or null when the run had none.
  const HybridScenarioResult* scenario(WalkScenario s) const;
};

/// Runs what `o.mode` asks for. Creates its own GL context (the caller
/// applies llvmpipe settings first). Throws InputError for input that
/// fails: a scene or path file, a model, `msaa` over what the GL offers.
HybridBenchResult run_hybrid(const HybridBenchOptions& o, const HybridBenchInputs& in);

}  // namespace terrasprite
