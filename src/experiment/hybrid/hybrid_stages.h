// SPDX-License-Identifier: MIT
// The walkthrough's stages shared by its files (not public): scoring,
// per-scenario summaries, and the two side studies (quality diagnosis,
// budget sweep) with the tables in context.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "terrasprite/experiment/hybrid/hybrid.h"
#include "terrasprite/hybrid/walkthrough_path.h"
#include "terrasprite/raster/scene.h"

namespace terrasprite::hybrid_bench {

/// Per-frame state the scorer shares with the frame callback: which frame
/// this is, and where the terrain alone is (object pixels are those in front
/// of it in either image).
struct ScoringState {
  int frame = -1;
  std::vector<float> terrain_depth;
  std::vector<int> flip_frames;
};

/// The key under which the scorer adds the object-masked SSIM to
/// QualityScore::figures (read once, into HybridFrame::ssim_objects).
inline constexpr const char* kSsimObjects = "ssim_objects";

/// Pixels where either depth image has something in front of the terrain
/// alone (`terrain`, the same size; linear depth, +inf where nothing was
/// drawn): the objects' pixels, on which `ssim_objects` is measured.
std::vector<std::uint8_t> object_mask(const std::vector<float>& ref_depth,
                                      const std::vector<float>& test_depth,
                                      const std::vector<float>& terrain);
/// Whole-frame SSIM, PSNR and FLIP (FLIP only on `state`'s flip frames)
/// and the SSIM over object_mask. `state` is updated by the run's frame
/// callback before each frame is scored.
Scorer hybrid_scorer(std::shared_ptr<ScoringState> state);

/// One scenario's frames: the driver's, joined with the selection's figures
/// recorded per frame number.
std::vector<HybridFrame> hybrid_frames(const RendererRun& run,
                                       const std::map<int, HybridFrameStats>& selection);
/// One scenario's run summarised (frame time against `target_ms`, quality
/// at `checkpoints`: a checkpoint not scored keeps SSIM 1).
HybridScenarioResult summarise(WalkScenario scenario, std::vector<HybridFrame> frames,
                               double target_ms, const std::vector<PathCheckpoint>& checkpoints);
/// The selection's time per frame and the optimal policy's objective against
/// greedy's over the frames that carry both.
SelectionFigures selection_figures(const std::vector<HybridFrame>& frames);

/// What diagnose_hybrid_quality needs from the bench's setup.
struct QualityDiagnosisInput {
  GlSceneObjects& set;
  const std::vector<QualityTable>& tables;
  Scene& ground;
  const std::vector<Camera>& path;
  const std::vector<PathCheckpoint>& checkpoints;
  int width = 0, height = 0, terrain_quads = 64;
  std::vector<DiagnosisCondition> conditions;
  std::string image_dir;  ///< when set: every image of the 'all' group, as PNG
  /// The tables in context, when measured: their prediction is reported
  /// next to the raw tables'.
  const std::vector<QualityTable>* context_tables = nullptr;
  int samples = 1;  ///< a pixel's, as the walkthrough draws
};
/// Per checkpoint, on-screen size bucket and representation: the tables'
/// predicted SSIM against the one measured.
std::vector<DiagnosisRow> diagnose_hybrid_quality(const QualityDiagnosisInput& in);

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
/// Returns per (model, representation) seen: error scale, predicted, measured.
std::vector<ContextCalibration> calibrate_tables_in_context(const QualityContextInput& in,
                                                            std::vector<QualityTable>& tables);

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
std::vector<BudgetSweepRow> quality_budget_sweep(const BudgetSweepInput& in);

}  // namespace terrasprite::hybrid_bench
