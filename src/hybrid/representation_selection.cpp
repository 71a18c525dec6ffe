// SPDX-License-Identifier: MIT
// The four selection policies over one frame's visible instances.
// paper: Jehaes, Lamotte & Tack (GRAPP 2008), section 3.3: the lowest
// impostor resolution reaching the target quality, meshes above a hard
// resolution limit, the budget left after the impostors spent on the meshes
// by Pareto optimisation of quality against cost; past it, the target
// quality lowered within the frame when the impostors would not fit.
#include "terrasprite/hybrid/representation_selection.h"

#include <algorithm>
#include <cmath>

namespace terrasprite {
namespace {

bool is_mesh(const RepresentationOption& o) {
  return o.rep.kind == ObjectKind::kMesh;
}

/// Fills cost and benefit of `s.option`.
FrameSelection& total(std::span<const InstanceOptions> instances, FrameSelection& s) {
  s.cost_ms = s.benefit = 0;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const RepresentationOption& o = instances[i].options[std::size_t(s.option[i])];
    s.cost_ms += o.cost_ms;
    s.benefit += benefit(instances[i], o);
  }
  return s;
}

int static_choice(const InstanceOptions& inst, double error_px) {
  int best = -1;  // coarsest mesh under the error; else the finest mesh
  for (std::size_t o = 0; o < inst.options.size(); ++o) {
    const RepresentationOption& r = inst.options[o];
    if (!is_mesh(r)) continue;
    if (r.error_px <= error_px &&
        (best < 0 || r.triangles < inst.options[std::size_t(best)].triangles))
      best = int(o);
  }
  if (best >= 0) return best;
  for (std::size_t o = 0; o < inst.options.size(); ++o)
    if (is_mesh(inst.options[o]) &&
        (best < 0 || inst.options[o].triangles > inst.options[std::size_t(best)].triangles))
      best = int(o);
  return best >= 0 ? best : 0;
}

/// The lowest relief resolution reaching `target` (at most `max_res`), or -1.
int impostor_choice(const InstanceOptions& inst, double target, int max_res) {
  int best = -1;
  for (std::size_t o = 0; o < inst.options.size(); ++o) {
    const RepresentationOption& r = inst.options[o];
    if (r.rep.kind != ObjectKind::kRelief || r.rep.resolution > max_res || r.ssim < target)
      continue;
    if (best < 0 || r.rep.resolution < inst.options[std::size_t(best)].rep.resolution)
      best = int(o);
  }
  return best;
}

/// Relief only: the table's choice for the target, else the finest relief.
int ibr_choice(const InstanceOptions& inst, double target) {
  const int c = impostor_choice(inst, target, 1 << 30);
  if (c >= 0) return c;
  int best = -1;
  for (std::size_t o = 0; o < inst.options.size(); ++o)
    if (inst.options[o].rep.kind == ObjectKind::kRelief &&
        (best < 0 ||
         inst.options[o].rep.resolution > inst.options[std::size_t(best)].rep.resolution))
      best = int(o);
  return best >= 0 ? best : 0;
}

/// The cheapest mesh of `inst`'s options (ms), or its cheapest option's when it has no mesh.
double cheapest_mesh_ms(const InstanceOptions& inst) {
  double mesh = INFINITY, any = INFINITY;
  for (const RepresentationOption& o : inst.options) {
    any = std::min(any, o.cost_ms);
    if (is_mesh(o)) mesh = std::min(mesh, o.cost_ms);
  }
  return std::isfinite(mesh) ? mesh : any;
}

/// The paper's impostor pass at `target`: per instance its impostor option
/// or -1 (a mesh); returns the impostors' time plus every mesh at its cheapest.
double impostor_pass(std::span<const InstanceOptions> instances, double target, int max_res,
                     std::vector<int>& choice) {
  choice.assign(instances.size(), -1);
  double ms = 0;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    choice[i] = impostor_choice(instances[i], target, max_res);
    ms += choice[i] >= 0 ? instances[i].options[std::size_t(choice[i])].cost_ms
                         : cheapest_mesh_ms(instances[i]);
  }
  return ms;
}

FrameSelection paper_selection(std::span<const InstanceOptions> instances, double budget_ms,
                               const PolicyOptions& options) {
  FrameSelection s;
  const int max_res = options.max_impostor_resolution;
  double floor_ms = impostor_pass(instances, options.target_ssim, max_res, s.option);
  if (options.fit_budget && options.fit_step > 0 && floor_ms > budget_ms) {
    // Lower the target until the impostors fit; where none does, the
    // lowest floor found.
    std::vector<int> choice;
    for (int k = 1; floor_ms > budget_ms; ++k) {
      const double t = options.target_ssim - k * options.fit_step;
      if (t < options.fit_min_ssim - 1e-9) break;
      const double ms = impostor_pass(instances, t, max_res, choice);
      if (ms < floor_ms) {
        floor_ms = ms;
        s.option = choice;
      }
    }
  }
  std::vector<InstanceOptions> meshes;
  std::vector<std::size_t> mesh_of;
  double impostor_ms = 0;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    if (s.option[i] >= 0) {
      impostor_ms += instances[i].options[std::size_t(s.option[i])].cost_ms;
    } else {
      meshes.push_back(instances[i]);
      mesh_of.push_back(i);
    }
  }
  std::vector<std::vector<int>> index_of;
  const auto items = knapsack_items(std::span<const InstanceOptions>(meshes), is_mesh, &index_of);
  const KnapsackSolution k = greedy_knapsack(items, budget_ms - impostor_ms);
  for (std::size_t m = 0; m < meshes.size(); ++m)
    s.option[mesh_of[m]] = index_of[m][std::size_t(k.choice[m])];
  return total(instances, s);
}

}  // namespace

const char* selection_policy_name(SelectionPolicy policy) {
  switch (policy) {
    case SelectionPolicy::kStatic:
      return "static";
    case SelectionPolicy::kGreedy:
      return "greedy";
    case SelectionPolicy::kPaper:
      return "paper";
    case SelectionPolicy::kOptimal:
      return "optimal";
    case SelectionPolicy::kImpostorOnly:
      return "ibr";
  }
  return "?";
}

FrameSelection select_representations(SelectionPolicy policy,
                                      std::span<const InstanceOptions> instances, double budget_ms,
                                      const PolicyOptions& options) {
  FrameSelection s;
  switch (policy) {
    case SelectionPolicy::kStatic:
      for (const InstanceOptions& inst : instances)
        s.option.push_back(static_choice(inst, options.static_error_px));
      return total(instances, s);
    case SelectionPolicy::kImpostorOnly:
      for (const InstanceOptions& inst : instances)
        s.option.push_back(ibr_choice(inst, options.target_ssim));
      return total(instances, s);
    case SelectionPolicy::kPaper:
      return paper_selection(instances, budget_ms, options);
    case SelectionPolicy::kGreedy:
    case SelectionPolicy::kOptimal: {
      const auto items =
          knapsack_items(instances, [](const RepresentationOption&) { return true; });
      if (policy == SelectionPolicy::kGreedy) {
        const KnapsackSolution g = greedy_knapsack(items, budget_ms);
        s.option = g.choice;
        s.objective_greedy = g.benefit;
      } else {
        const KnapsackSolution o = optimal_knapsack(items, budget_ms, options.optimal);
        s.option = o.choice;
        s.objective_greedy = o.greedy_benefit;
        s.objective_optimal = o.benefit;
      }
      return total(instances, s);
    }
  }
  return s;
}

}  // namespace terrasprite
