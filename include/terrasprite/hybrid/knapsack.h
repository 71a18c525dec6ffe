// SPDX-License-Identifier: MIT
// The multiple-choice knapsack behind per-frame representation selection:
// every visible instance (an item) takes exactly one of its representations
// (choices), each with an expected draw cost and a benefit; maximise the
// total benefit with the total cost under a budget.
// The gap's figures: docs/results/2026-12-07-hybrid-defaults.md
#pragma once
#include <span>
#include <vector>

namespace terrasprite {

/// One representation of one instance.
struct KnapsackChoice {
  double cost = 0;     ///< expected draw time, ms (>= 0)
  double benefit = 0;  ///< expected quality x on-screen weight (>= 0)
};

/// One instance: at least one choice.
struct KnapsackItem {
  std::vector<KnapsackChoice> choices;
};

/// A solution: one choice index per item.
struct KnapsackSolution {
  std::vector<int> choice;
  double cost = 0;
  double benefit = 0;
  /// Upper bound on the optimum (LP relaxation); equal to `benefit` when
  /// proven optimal. Only the optimal solver sets it; 0 otherwise.
  double upper_bound = 0;
  bool proven_optimal = false;
  /// The optimal solver's greedy solution's benefit on the same items (it
  /// solves both); 0 from the other solvers.
  double greedy_benefit = 0;
};

/// Cost and benefit of `choice` (one index per item).
KnapsackSolution evaluate(std::span<const KnapsackItem> items, std::vector<int> choice);

/// Every item at its cheapest choice (ties: the larger benefit); the answer
/// whenever even that exceeds the budget.
KnapsackSolution cheapest(std::span<const KnapsackItem> items);

/// Funkhouser & Sequin (SIGGRAPH 1993), section 4.2: start every item at its
/// cheapest choice and take upgrades along each item's convex hull of
/// benefit over cost in falling benefit/cost order while they fit. At worst
/// half the optimum; O(n k log(n k)).
KnapsackSolution greedy_knapsack(std::span<const KnapsackItem> items, double budget);

struct OptimalOptions {
  /// Items around the LP relaxation's fractional break (by the ratio of
  /// their hull steps to the break ratio) searched exactly; the others keep
  /// their LP choice. All items when there are at most this many.
  int core_items = 16;
  long long node_limit = 1500;  ///< branch-and-bound nodes; best found so far after
  /// The stated optimality gap, relative: where greedy's benefit is within
  /// this fraction of the LP bound, it is returned (with that bound in
  /// `upper_bound`) without the search, which gains little over greedy at
  /// several times its time. 0: always search.
  double gap = 1e-3;
};

/// Lagrangian (LP) relaxation for the bound and the break item, then a
/// depth-first branch and bound over the core items' undominated choices
/// bounded by the LP of the items not yet fixed (Pisinger's core idea for
/// the MCKP). Returns the better of that and greedy_knapsack: never below
/// greedy, and within `options.gap` of the optimum. `upper_bound` -
/// `benefit` is the remaining optimality gap.
KnapsackSolution optimal_knapsack(std::span<const KnapsackItem> items, double budget,
                                  const OptimalOptions& options = {});

/// Exhaustive search (tests; k^n).
KnapsackSolution brute_force_knapsack(std::span<const KnapsackItem> items, double budget);

}  // namespace terrasprite
