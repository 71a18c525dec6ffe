// SPDX-License-Identifier: MIT
// Multiple-choice knapsack, solved to optimality on a core: Sinha & Zoltners
// (Oper. Res. 1979) for the LP (Lagrangian) relaxation of the MCKP -- hull
// steps in falling benefit/cost order up to the break step --, and Pisinger
// ("A minimal algorithm for the multiple-choice knapsack problem", EJOR 1995)
// for searching only the items around the break exactly.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "hybrid/knapsack_hull.h"
#include "terrasprite/hybrid/knapsack.h"

namespace terrasprite {
namespace {

using knapsack::Step;

/// The LP relaxation: every item on its hull, steps taken whole up to the
/// break step, which is taken in part.
struct Relaxation {
  std::vector<int> choice;  ///< the whole steps' choices
  double value = 0;         ///< LP optimum (an upper bound)
  double break_ratio = 0;   ///< lambda*: benefit/cost of the break step (0: none)
  bool feasible = true;
};

Relaxation relax(std::span<const KnapsackItem> items, const std::vector<std::vector<int>>& hulls,
                 const std::vector<Step>& steps, double budget) {
  Relaxation r;
  double cost = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    r.choice.push_back(hulls[i].front());
    cost += items[i].choices[std::size_t(hulls[i].front())].cost;
    r.value += items[i].choices[std::size_t(hulls[i].front())].benefit;
  }
  if (cost > budget) {
    r.feasible = false;
    return r;
  }
  for (const Step& s : steps) {
    if (cost + s.cost > budget) {
      r.value += s.benefit * (budget - cost) / s.cost;
      r.break_ratio = s.ratio();
      break;
    }
    cost += s.cost;
    r.value += s.benefit;
    r.choice[std::size_t(s.item)] = s.to;
  }
  return r;
}

/// Depth-first branch and bound over the core items; the rest stay fixed.
class CoreSearch {
 public:
  CoreSearch(std::span<const KnapsackItem> items, const knapsack::Prepared& p,
             std::vector<int> core, long long node_limit)
      : items_(items), core_(std::move(core)), node_limit_(node_limit) {
    std::vector<int> depth_of(items.size(), -1);
    for (std::size_t d = 0; d < core_.size(); ++d) {
      const std::size_t i = std::size_t(core_[d]);
      depth_of[i] = int(d);
      // Best benefit first: the incumbent improves early.
      options_.emplace_back(p.undominated[i].rbegin(), p.undominated[i].rend());
      hulls_.push_back(p.hulls[i]);
    }
    // The core's hull steps (already in ratio order), by depth: the LP over
    // the items from depth d on bounds a node at depth d.
    for (Step s : p.steps)
      if (depth_of[std::size_t(s.item)] >= 0) {
        s.item = depth_of[std::size_t(s.item)];
        steps_.push_back(s);
      }
    suffix_min_cost_.assign(core_.size() + 1, 0.0);
    suffix_min_benefit_.assign(core_.size() + 1, 0.0);
    for (std::size_t d = core_.size(); d-- > 0;) {
      const KnapsackChoice& c =
          items[std::size_t(core_[d])].choices[std::size_t(hulls_[d].front())];
      suffix_min_cost_[d] = suffix_min_cost_[d + 1] + c.cost;
      suffix_min_benefit_[d] = suffix_min_benefit_[d + 1] + c.benefit;
    }
  }

  /// Improves `best_choice` (indexed by item) when it finds better for `budget`
  /// left to the core; returns whether the search finished.
  bool run(double budget, double incumbent_core_benefit, std::vector<int>& best_choice) {
    best_ = incumbent_core_benefit;
    current_.assign(core_.size(), -1);
    best_core_.clear();
    search(0, budget, 0.0);
    if (!best_core_.empty())
      for (std::size_t d = 0; d < core_.size(); ++d)
        best_choice[std::size_t(core_[d])] = best_core_[d];
    return nodes_ <= node_limit_;
  }

 private:
  double bound(std::size_t depth, double left) const {
    left -= suffix_min_cost_[depth];
    if (left < 0) return -1;
    double value = suffix_min_benefit_[depth];
    for (const Step& s : steps_) {
      if (std::size_t(s.item) < depth) continue;
      if (s.cost > left) return value + s.benefit * left / s.cost;
      left -= s.cost;
      value += s.benefit;
    }
    return value;
  }

  void search(std::size_t depth, double left, double benefit) {
    if (++nodes_ > node_limit_) return;
    if (depth == core_.size()) {
      if (benefit > best_) {
        best_ = benefit;
        best_core_ = current_;
      }
      return;
    }
    const KnapsackItem& item = items_[std::size_t(core_[depth])];
    for (int c : options_[depth]) {
      const KnapsackChoice& ch = item.choices[std::size_t(c)];
      const double l = left - ch.cost;
      const double b = bound(depth + 1, l);
      if (b < 0 || benefit + ch.benefit + b <= best_ + 1e-12 * std::abs(best_)) continue;
      current_[depth] = c;
      search(depth + 1, l, benefit + ch.benefit);
    }
  }

  std::span<const KnapsackItem> items_;
  std::vector<int> core_;
  long long node_limit_;
  long long nodes_ = 0;
  std::vector<std::vector<int>> options_, hulls_;
  std::vector<Step> steps_;
  std::vector<double> suffix_min_cost_, suffix_min_benefit_;
  std::vector<int> current_, best_core_;
  double best_ = 0;
};

/// The `count` items whose hull steps come nearest the break ratio
/// (log-ratio distance), nearest first.
std::vector<int> core_items(std::span<const KnapsackItem> items, const std::vector<Step>& steps,
                            double break_ratio, int count) {
  std::vector<double> distance(items.size(), INFINITY);
  const double lb = std::log(std::max(break_ratio, 1e-300));
  for (const Step& s : steps) {
    const double d = std::abs(std::log(std::max(s.ratio(), 1e-300)) - lb);
    distance[std::size_t(s.item)] = std::min(distance[std::size_t(s.item)], d);
  }
  std::vector<int> order(items.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return distance[a] < distance[b]; });
  order.resize(std::min<std::size_t>(order.size(), std::size_t(count)));
  return order;
}

}  // namespace

KnapsackSolution optimal_knapsack(std::span<const KnapsackItem> items, double budget,
                                  const OptimalOptions& options) {
  const knapsack::Prepared prepared = knapsack::prepare(items);
  KnapsackSolution greedy = knapsack::greedy(items, prepared, budget);
  greedy.greedy_benefit = greedy.benefit;
  if (greedy.cost > budget) return greedy;  // even the cheapest choices exceed it
  const std::vector<Step>& steps = prepared.steps;
  const Relaxation lp = relax(items, prepared.hulls, steps, budget);
  const double tolerance = 1e-9 * std::max(1.0, std::abs(lp.value));
  KnapsackSolution best = greedy;
  bool searched_all = false;
  // Within the stated gap of the bound, the search could gain at most the gap.
  if (greedy.benefit < lp.value * (1 - std::max(0.0, options.gap)) - tolerance) {
    // Items outside the core keep their LP choice; the core starts from the
    // LP choice too (feasible: whole steps only) and is searched exactly.
    const std::vector<int> core =
        items.size() <= std::size_t(options.core_items)
            ? [&] { std::vector<int> all(items.size()); std::iota(all.begin(), all.end(), 0); return all; }()
            : core_items(items, steps, lp.break_ratio, options.core_items);
    std::vector<int> choice = lp.choice;
    double fixed_cost = 0, core_benefit = 0;
    std::vector<char> in_core(items.size(), 0);
    for (int i : core) in_core[std::size_t(i)] = 1;
    for (std::size_t i = 0; i < items.size(); ++i) {
      const KnapsackChoice& c = items[i].choices[std::size_t(choice[i])];
      if (in_core[i])
        core_benefit += c.benefit;
      else
        fixed_cost += c.cost;
    }
    CoreSearch search(items, prepared, core, options.node_limit);
    const bool finished = search.run(budget - fixed_cost, core_benefit - 1e-12, choice);
    searched_all = finished && core.size() == items.size();
    KnapsackSolution own = evaluate(items, std::move(choice));
    if (own.benefit >= greedy.benefit) best = std::move(own);
  }
  best.greedy_benefit = greedy.benefit;
  best.upper_bound = std::max(lp.value, best.benefit);
  best.proven_optimal = searched_all || best.benefit >= lp.value - tolerance;
  if (best.proven_optimal) best.upper_bound = best.benefit;
  return best;
}

}  // namespace terrasprite
