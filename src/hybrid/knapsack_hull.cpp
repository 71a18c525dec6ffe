// SPDX-License-Identifier: MIT
#include "hybrid/knapsack_hull.h"

#include <algorithm>
#include <cassert>
#include <numeric>

namespace terrasprite::knapsack {

std::vector<int> undominated(const KnapsackItem& item) {
  assert(!item.choices.empty());
  std::vector<int> order(item.choices.size());
  std::iota(order.begin(), order.end(), 0);
  const auto& c = item.choices;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return c[a].cost != c[b].cost ? c[a].cost < c[b].cost : c[a].benefit > c[b].benefit;
  });
  std::vector<int> kept;
  for (int i : order)
    if (kept.empty() || c[i].benefit > c[kept.back()].benefit) kept.push_back(i);
  return kept;
}

std::vector<int> hull(const KnapsackItem& item, const std::vector<int>& undominated) {
  const auto& c = item.choices;
  std::vector<int> h;
  for (int i : undominated) {
    // Drop the last hull point while it lies on or under the chord to i.
    while (h.size() >= 2) {
      const KnapsackChoice& a = c[h[h.size() - 2]];
      const KnapsackChoice& b = c[h.back()];
      const double cross = (b.cost - a.cost) * (c[i].benefit - a.benefit) -
                           (b.benefit - a.benefit) * (c[i].cost - a.cost);
      if (cross < 0) break;
      h.pop_back();
    }
    h.push_back(i);
  }
  return h;
}

std::vector<Step> sorted_steps(std::span<const KnapsackItem> items,
                               const std::vector<std::vector<int>>& hulls) {
  std::vector<Step> steps;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const auto& h = hulls[i];
    for (std::size_t j = 1; j < h.size(); ++j) {
      const KnapsackChoice& a = items[i].choices[h[j - 1]];
      const KnapsackChoice& b = items[i].choices[h[j]];
      steps.push_back({int(i), h[j - 1], h[j], b.cost - a.cost, b.benefit - a.benefit});
    }
  }
  // Hull ratios fall along an item, so a stable sort keeps each item's steps in order.
  std::stable_sort(steps.begin(), steps.end(), [](const Step& a, const Step& b) {
    return a.benefit * b.cost > b.benefit * a.cost;
  });
  return steps;
}

Prepared prepare(std::span<const KnapsackItem> items) {
  Prepared p;
  p.undominated.reserve(items.size());
  p.hulls.reserve(items.size());
  for (const KnapsackItem& item : items) {
    p.undominated.push_back(undominated(item));
    p.hulls.push_back(hull(item, p.undominated.back()));
  }
  p.steps = sorted_steps(items, p.hulls);
  return p;
}

}  // namespace terrasprite::knapsack
