// SPDX-License-Identifier: MIT
// Per-frame choice of a representation for every visible object instance,
// under a draw-time budget, by one of four policies: static distance
// thresholds, greedy (Funkhouser & Sequin 1993), the paper's (Jehaes,
// Lamotte & Tack, GRAPP 2008) and the optimal multiple-choice knapsack.
#pragma once
#include <span>
#include <string>
#include <vector>

#include "terrasprite/hybrid/knapsack.h"
#include "terrasprite/objects/object_renderer.h"

namespace terrasprite {

/// One representation an instance could be drawn with, as the frame sees it.
struct RepresentationOption {
  Representation rep;
  double cost_ms = 0;       ///< expected draw time (cost model)
  double ssim = 1;          ///< expected quality (tables, interpolated)
  double psnr = 100;        ///< dB
  long long triangles = 0;  ///< per instance
  double error_px = 0;      ///< LOD level's geometric error on screen (meshes; 0 otherwise)
  /// What the caller took off the tables' expected SSIM to get `ssim`
  /// (HybridOptions::quality_spread_penalty): the frame is expected to
  /// score ssim + penalty.
  double penalty = 0;
};

/// The mesh level that marks an option as "not drawn": the instance is left
/// out of the frame (no triangles, no cost, expected SSIM 0, the quality of
/// an object that is not there). HybridOptions::cull_px offers it to small
/// instances, so that the policy may leave them out instead of drawing
/// every visible instance at least at its cheapest.
inline constexpr int kNotDrawnLevel = -1;
inline bool is_drawn(const Representation& r) {
  return !(r.kind == ObjectKind::kMesh && r.level == kNotDrawnLevel);
}
inline RepresentationOption not_drawn_option() {
  return {Representation{ObjectKind::kMesh, kNotDrawnLevel, 0, 0}, 0.0, 0.0, 0.0, 0, 0.0};
}

/// One visible instance and its options (at least one).
struct InstanceOptions {
  int instance = 0;    ///< caller's id, stable across frames (hysteresis keys on it)
  double size_px = 0;  ///< on-screen diameter
  /// Benefit weight of the instance: its expected quality counts in
  /// proportion to the image area it covers, (size_px^2) / (width * height).
  double weight = 0;
  std::vector<RepresentationOption> options;
};

enum class SelectionPolicy { kStatic, kGreedy, kPaper, kOptimal, kImpostorOnly };
/// "static", "greedy", "paper", "optimal", "ibr" (as reports name them).
const char* selection_policy_name(SelectionPolicy policy);

struct PolicyOptions {
  /// static: the coarsest LOD level whose error stays under this on screen.
  double static_error_px = 1.0;
  /// paper / ibr: the lowest relief resolution reaching this expected SSIM.
  double target_ssim = 0.95;
  /// paper: impostors above this resolution are drawn as a mesh instead.
  int max_impostor_resolution = 128;
  /// paper, past it: when the impostors reaching `target_ssim` and every
  /// mesh at its cheapest do not fit the budget, the target is lowered by
  /// `fit_step` (down to `fit_min_ssim`) until they do, in this frame (the
  /// paper's controller only learns it from the measured frame, a step per
  /// frame, so its first frames run over the target). The floor stays near
  /// the tables' 0.95: lower targets pick relief impostors whose quality in
  /// the scene is far under their tables'.
  /// Figures: docs/results/2026-12-07-hybrid-fit-budget.md.
  bool fit_budget = true;
  double fit_step = 0.01, fit_min_ssim = 0.90;
  OptimalOptions optimal;
};

struct FrameSelection {
  std::vector<int> option;  ///< per InstanceOptions entry: index into its options
  double cost_ms = 0;       ///< expected draw time of the choice
  double benefit = 0;       ///< sum of weight x expected SSIM
  /// Greedy's and optimal's objective on the same instances and budget
  /// (optimal solves both; greedy sets its own only; others: -1).
  double objective_greedy = -1, objective_optimal = -1;
};

/// Benefit of drawing `instance` with option `o`.
inline double benefit(const InstanceOptions& instance, const RepresentationOption& o) {
  return instance.weight * o.ssim;
}

/// Chooses for every instance. `budget_ms` is the objects' share of the
/// frame (static and ibr ignore it). Instances not passed (outside the view)
/// are not drawn and cost nothing.
FrameSelection select_representations(SelectionPolicy policy,
                                      std::span<const InstanceOptions> instances, double budget_ms,
                                      const PolicyOptions& options = {});

/// The knapsack of `instances` restricted to the options `keep` accepts
/// (an instance with none accepted keeps all its options).
template <class Keep>
std::vector<KnapsackItem> knapsack_items(std::span<const InstanceOptions> instances, Keep keep,
                                         std::vector<std::vector<int>>* index_of = nullptr) {
  std::vector<KnapsackItem> items;
  for (const InstanceOptions& inst : instances) {
    KnapsackItem item;
    std::vector<int> idx;
    for (std::size_t o = 0; o < inst.options.size(); ++o)
      if (keep(inst.options[o])) {
        item.choices.push_back({inst.options[o].cost_ms, benefit(inst, inst.options[o])});
        idx.push_back(int(o));
      }
    if (item.choices.empty())
      for (std::size_t o = 0; o < inst.options.size(); ++o) {
        item.choices.push_back({inst.options[o].cost_ms, benefit(inst, inst.options[o])});
        idx.push_back(int(o));
      }
    items.push_back(std::move(item));
    if (index_of) index_of->push_back(std::move(idx));
  }
  return items;
}

}  // namespace terrasprite
