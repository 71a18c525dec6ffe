// SPDX-License-Identifier: MIT
// The convex hull of one knapsack item's choices (benefit over cost), shared
// by the greedy and the optimal solver: the steps from one hull choice to
// the next, in falling benefit/cost order.
#pragma once
#include <span>
#include <vector>

#include "terrasprite/hybrid/knapsack.h"

namespace terrasprite::knapsack {

/// Choices of `item` that no cheaper-or-equal choice beats or equals in
/// benefit, in rising cost.
std::vector<int> undominated(const KnapsackItem& item);

/// The upper convex hull of `undominated` choices (indices into item.choices),
/// cheapest first.
std::vector<int> hull(const KnapsackItem& item, const std::vector<int>& undominated);

/// An upgrade along an item's hull.
struct Step {
  int item = 0;
  int from = 0, to = 0;  ///< choice indices
  double cost = 0, benefit = 0;
  double ratio() const { return benefit / cost; }
};

/// Every item's hull steps, sorted by falling ratio (an item's own steps stay
/// in hull order).
std::vector<Step> sorted_steps(std::span<const KnapsackItem> items,
                               const std::vector<std::vector<int>>& hulls);

/// Everything the solvers derive from the items once: per item its
/// undominated choices and hull, and all hull steps in falling ratio order.
struct Prepared {
  std::vector<std::vector<int>> undominated, hulls;
  std::vector<Step> steps;
};
Prepared prepare(std::span<const KnapsackItem> items);

/// greedy_knapsack on prepared items.
KnapsackSolution greedy(std::span<const KnapsackItem> items, const Prepared& p, double budget);

}  // namespace terrasprite::knapsack
