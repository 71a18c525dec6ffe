// SPDX-License-Identifier: MIT
// A scene's objects drawn each frame with representations chosen under a
// frame-time budget (Jehaes, Lamotte & Tack, GRAPP 2008, and past it): every
// visible instance's options come from its model's quality tables and the
// cost model, a policy picks, hysteresis steadies the picks, a controller
// holds the target frame time from measured frames.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "terrasprite/hybrid/budget_controller.h"
#include "terrasprite/hybrid/draw_cost_model.h"
#include "terrasprite/hybrid/frame_pace.h"
#include "terrasprite/hybrid/representation_selection.h"
#include "terrasprite/hybrid/selection_hysteresis.h"
#include "terrasprite/objects/gl_scene_objects.h"
#include "terrasprite/objects/quality_table.h"

namespace terrasprite {

/// How one scenario draws the objects.
struct HybridScenario {
  std::string name;
  /// Representations offered (a model's table rows of these kinds).
  std::vector<ObjectKind> kinds{ObjectKind::kMesh};
  SelectionPolicy policy = SelectionPolicy::kStatic;
  /// Every visible instance at full geometry (the reference), ignoring the rest.
  bool full = false;
  enum class Control {
    kNone,         ///< unbudgeted (full, ibr) or a fixed budget
    kQualityStep,  ///< the paper's: target quality up/down with the frame time (and the PI budget)
    kBudgetPi,     ///< cost-model prediction corrected by measured time (PI)
    kFixed,        ///< HybridOptions::target_ms as the budget, in predicted ms (no feedback)
  } control = Control::kNone;
  /// Instances hidden behind what is already drawn (the terrain) are left
  /// out before selection (DepthOcclusion: conservative, the image does not
  /// change). Costs one depth read-back a frame. Only into a viewport of
  /// exactly HybridOptions' width x height (otherwise nothing is culled).
  /// The bench's `full` turns it off: the paper's full geometry draws every
  /// instance in the frustum.
  bool cull_occluded = true;
};

struct HybridOptions {
  int width = 1280, height = 720;
  double target_ms = 100;
  PolicyOptions policy;
  HysteresisOptions hysteresis;
  bool use_hysteresis = true;
  /// Impostors are not offered to instances larger than this on screen
  /// (0: no limit; `ibr` always gets them): the bench passes 2x the
  /// tables' largest size, past which their quality is extrapolated (and an
  /// impostor of an object beside the camera is far worse than its table:
  /// docs/results/2026-12-07-hybrid-max-impostor-size.md).
  double max_impostor_size_px = 0;
  /// The policies weigh an option at its expected SSIM less this many times
  /// its table's spread near the view (ExpectedQuality::ssim_spread), so
  /// that a choice among many options does not go to the ones whose table
  /// happens to be most optimistic (the optimiser's curse). 0: the tables'
  /// value as it is, the default (a penalty has not been shown to help;
  /// docs/results/2026-12-05-hybrid-quality-spread-penalty.md).
  double quality_spread_penalty = 0;
  /// Budgeted policies (not `full`, not `ibr`) may leave instances whose
  /// on-screen diameter is under this many pixels undrawn: such an instance
  /// also gets not_drawn_option() (cost 0, expected SSIM 0), weighed by the
  /// policy like its other options: it is left out when drawing it gains
  /// less per millisecond than what the budget buys elsewhere, which a
  /// tight budget makes likely. 0: every visible instance is drawn, at its
  /// cheapest at least, even where that floor alone is over the budget
  /// (many instances a few pixels wide) and the nearest ones then get their
  /// cheapest too (docs/results/2026-12-01-hybrid-not-drawn.md).
  double cull_px = 0;
  /// The objects' budget (the frame's, less the terrain and the draw calls
  /// the policy cannot see, at the read-back's pace) never falls below this
  /// fraction of the median of the previous `objects_budget_window` frames'
  /// (as computed, before this floor; 0: no floor). The loop, the cost
  /// model's refit and the read-back's pace all answer one slow frame, and
  /// together they would cut the objects' budget to a fraction of its usual
  /// for a frame or several (every instance near its coarsest).
  /// Figures: docs/results/2026-12-03-hybrid-objects-budget-floor.md.
  double objects_budget_floor = 0.6;
  int objects_budget_window = 9;
  BudgetControllerOptions controller;  ///< target_ms is set from target_ms above
  QualityStepOptions quality_step;     ///< likewise
  FramePaceOptions pace;               ///< max_slope 0: no pace
};

/// What the last frame's selection did.
struct HybridFrameStats {
  int visible = 0;   ///< in the frustum and not hidden behind the terrain
  int occluded = 0;  ///< in the frustum but behind the terrain (HybridScenario::cull_occluded)
  /// Depth read-back (mostly waiting for the terrain's rasterisation) and
  /// occlusion pyramid, wall time; not in selection_ms.
  double occlusion_ms = 0;
  /// View, occlusion tests, options and policy: wall time on the drawing
  /// thread. With occlusion culling the viewing and pricing run on another
  /// thread beside the read-back (view_ms), and only a wait for them counts.
  double selection_ms = 0;
  /// Viewing and pricing every instance in the frustum, wall time on the
  /// thread that ran it: the work selection_ms no longer holds when it ran
  /// beside the read-back.
  double view_ms = 0;
  double policy_ms = 0;  ///< of selection_ms, the policy and hysteresis
  /// The factor on the frame's prediction after the read-back for the
  /// machine's pace it showed (FramePace; 1 without occlusion culling).
  double pace = 1;
  double predicted_ms = 0;  ///< cost model: terrain term + chosen objects
  double budget_ms = 0;     ///< whole-frame budget handed to the policy (predicted ms)
  /// Of it, the objects' (HybridOptions::objects_budget_floor applied), ms;
  /// infinite when unbudgeted.
  double objects_budget_ms = 0;
  double target_quality = 0;  ///< the paper controller's SSIM target (others: the fixed one)
  double benefit = 0;         ///< sum of weight x expected SSIM
  double expected_ssim = 0;   ///< weight-averaged expected SSIM of the visible instances
  double objective_greedy = -1, objective_optimal = -1;
  int switches = 0;
  long long triangles = 0, triangles_min = 0, triangles_max = 0;  ///< chosen, cheapest, full
  std::array<int, 3> instances_by_kind{};                         ///< drawn instances
  std::array<int, 3> draws_by_kind{};  ///< draw calls ((model, representation) groups)
  int not_drawn = 0;  ///< visible instances the policy left out (HybridOptions::cull_px)
  /// Expected cost of every visible instance at its cheapest option (the
  /// policy's floor: under it, nothing can be upgraded), ms.
  double floor_ms = 0;
  /// Predicted draw calls the policy could not see (taken off the next budget), ms.
  double draw_gap_ms = 0;
  /// Of predicted_ms, per kind (indexed by ObjectKind): its instances and
  /// draw calls at the read-back's pace (without the frame term and the
  /// terrain's known deviation), ms.
  std::array<double, 3> predicted_by_kind_ms{};
};

class HybridObjects : public SceneObjects {
 public:
  /// `tables[i]` is model i's table (its representations; rows of kinds the
  /// scenario does not offer are ignored). `cost` is copied and refit online
  /// from feedback(). The set must outlive this.
  HybridObjects(GlSceneObjects& set, const std::vector<QualityTable>& tables,
                const DrawCostModel& cost, HybridScenario scenario, const HybridOptions& options);
  ~HybridObjects() override;

  /// Selects and draws every visible instance; returns the triangles. On the
  /// thread that owns the GL context; with occlusion culling it views the
  /// instances on a TBB worker during the depth read-back, joined before the
  /// choice (it reads only the set, the tables and the cost model).
  long long draw(const Camera& camera) override;
  /// The measured time of the whole frame just drawn (terrain included).
  void feedback(double measured_ms);
  /// Back to the state before the first frame: the calibrated cost model,
  /// fresh controllers and hysteresis. For after untimed warm-up draws (a
  /// cold first draw runs far over its prediction and would cut the first
  /// timed frame's budget).
  void forget_feedback();
  const HybridFrameStats& last() const { return last_; }
  const HybridScenario& scenario() const { return scenario_; }
  /// Builds every impostor the scenario may draw (before timing anything).
  void prepare();
  /// Diagnosis (`bench hybrid --cost-split`): from the next draw on, only
  /// instances of the kinds set here (indexed by ObjectKind) are drawn; the
  /// selection, its stats and the cost model go on as if all were. Default:
  /// every kind.
  void set_drawn_kinds(const std::array<bool, 3>& kinds);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  HybridScenario scenario_;
  HybridFrameStats last_;
};

}  // namespace terrasprite
