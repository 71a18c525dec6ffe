// SPDX-License-Identifier: MIT
// Funkhouser & Sequin, "Adaptive display algorithm for interactive frame
// rates during visualization of complex virtual environments", SIGGRAPH 1993,
// section 4.2: upgrades in benefit/cost order while they fit.
#include <cassert>
#include <limits>

#include "hybrid/knapsack_hull.h"
#include "terrasprite/hybrid/knapsack.h"

namespace terrasprite {

KnapsackSolution evaluate(std::span<const KnapsackItem> items, std::vector<int> choice) {
  assert(choice.size() == items.size());
  KnapsackSolution s;
  for (std::size_t i = 0; i < items.size(); ++i) {
    s.cost += items[i].choices[std::size_t(choice[i])].cost;
    s.benefit += items[i].choices[std::size_t(choice[i])].benefit;
  }
  s.choice = std::move(choice);
  return s;
}

KnapsackSolution cheapest(std::span<const KnapsackItem> items) {
  std::vector<int> choice;
  choice.reserve(items.size());
  for (const KnapsackItem& item : items) choice.push_back(knapsack::undominated(item).front());
  return evaluate(items, std::move(choice));
}

namespace knapsack {

KnapsackSolution greedy(std::span<const KnapsackItem> items, const Prepared& p, double budget) {
  std::vector<int> choice;
  choice.reserve(items.size());
  double cost = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    choice.push_back(p.hulls[i].front());
    cost += items[i].choices[std::size_t(choice.back())].cost;
  }
  double left = budget - cost;
  if (left >= 0)
    for (const Step& step : p.steps) {
      // An item whose step did not fit stays where it is: its later steps start elsewhere.
      if (choice[std::size_t(step.item)] != step.from || step.cost > left) continue;
      choice[std::size_t(step.item)] = step.to;
      left -= step.cost;
    }
  return evaluate(items, std::move(choice));
}

}  // namespace knapsack

KnapsackSolution greedy_knapsack(std::span<const KnapsackItem> items, double budget) {
  return knapsack::greedy(items, knapsack::prepare(items), budget);
}

KnapsackSolution brute_force_knapsack(std::span<const KnapsackItem> items, double budget) {
  std::vector<int> choice(items.size(), 0);
  KnapsackSolution best = cheapest(items);
  bool found = false;
  for (;;) {
    KnapsackSolution s = evaluate(items, choice);
    if (s.cost <= budget && (!found || s.benefit > best.benefit)) {
      best = s;
      found = true;
    }
    std::size_t i = 0;
    while (i < items.size() && ++choice[i] == int(items[i].choices.size())) choice[i++] = 0;
    if (i == items.size()) break;
  }
  best.proven_optimal = found;
  best.upper_bound = best.benefit;
  return best;
}

}  // namespace terrasprite
