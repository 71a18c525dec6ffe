// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "terrasprite/hybrid/knapsack.h"

namespace terrasprite {
namespace {

std::vector<KnapsackItem> random_items(int n, int k, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<KnapsackItem> items(static_cast<std::size_t>(n));
  for (KnapsackItem& item : items)
    for (int j = 0; j < k; ++j) item.choices.push_back({u(rng) * 10.0, u(rng) * 5.0});
  return items;
}

double total_cheapest(const std::vector<KnapsackItem>& items) {
  return cheapest(items).cost;
}

/// One of 300 small instances (6 items x 4 choices, a seeded budget over
/// the cheapest), with brute force's and greedy's answers to it.
struct SmallCase {
  std::vector<KnapsackItem> items;
  double budget = 0;
  KnapsackSolution brute, greedy;
};

SmallCase small_case(unsigned seed) {
  SmallCase c;
  c.items = random_items(6, 4, seed);
  std::mt19937 rng(seed + 1000);
  c.budget = total_cheapest(c.items) + std::uniform_real_distribution<double>(0, 15)(rng);
  c.brute = brute_force_knapsack(c.items, c.budget);
  c.greedy = greedy_knapsack(c.items, c.budget);
  return c;
}

TEST(Knapsack, OptimalMatchesBruteForceAndGreedyNeverBeatsIt) {
  OptimalOptions exact;
  exact.gap = 0;
  for (unsigned seed = 1; seed <= 300; ++seed) {
    const SmallCase c = small_case(seed);
    const KnapsackSolution opt = optimal_knapsack(c.items, c.budget, exact);
    ASSERT_NEAR(opt.benefit, c.brute.benefit, 1e-9) << "seed " << seed;
    EXPECT_LE(opt.cost, c.budget + 1e-12) << "seed " << seed;
    EXPECT_TRUE(opt.proven_optimal) << "seed " << seed;
    EXPECT_LE(c.greedy.benefit, opt.benefit + 1e-12) << "seed " << seed;
    EXPECT_LE(c.greedy.cost, c.budget + 1e-12) << "seed " << seed;
  }
}

TEST(Knapsack, WithinTheStatedGapOfBruteForce) {
  // A gap as wide as 5% makes the shortcut (greedy, no search) common on
  // these instances: it still never returns less than 95% of the optimum,
  // nor less than greedy, and its bound is true.
  OptimalOptions wide;
  wide.gap = 0.05;
  int shortcuts = 0;
  for (unsigned seed = 1; seed <= 300; ++seed) {
    const SmallCase c = small_case(seed);
    const KnapsackSolution opt = optimal_knapsack(c.items, c.budget, wide);
    EXPECT_GE(opt.benefit, 0.95 * c.brute.benefit - 1e-9) << "seed " << seed;
    EXPECT_GE(opt.benefit, c.greedy.benefit - 1e-12) << "seed " << seed;
    EXPECT_GE(opt.upper_bound, c.brute.benefit - 1e-9) << "seed " << seed;
    EXPECT_LE(opt.cost, c.budget + 1e-12) << "seed " << seed;
    if (opt.benefit < c.brute.benefit - 1e-9) ++shortcuts;
  }
  EXPECT_GT(shortcuts, 0);  // the gap was used
}

TEST(Knapsack, CoreSearchNeverBelowGreedyOnLargeInstances) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const auto items = random_items(400, 12, seed);
    const double budget = total_cheapest(items) + 600.0;
    const KnapsackSolution opt = optimal_knapsack(items, budget);
    const KnapsackSolution greedy = greedy_knapsack(items, budget);
    EXPECT_GE(opt.benefit, greedy.benefit) << "seed " << seed;
    EXPECT_LE(opt.cost, budget + 1e-9);
    EXPECT_GE(opt.upper_bound, opt.benefit);
    // The LP bound leaves at most one step's benefit open.
    EXPECT_LT(opt.upper_bound - opt.benefit, 5.0) << "seed " << seed;
  }
}

TEST(Knapsack, ZeroAndInfiniteBudget) {
  const auto items = random_items(8, 5, 7);
  const KnapsackSolution none = optimal_knapsack(items, 0.0);
  const KnapsackSolution low = cheapest(items);
  EXPECT_EQ(none.choice, low.choice);  // over budget: everything at its cheapest
  const KnapsackSolution all = optimal_knapsack(items, INFINITY);
  for (std::size_t i = 0; i < items.size(); ++i) {
    double best = 0;
    for (const KnapsackChoice& c : items[i].choices) best = std::max(best, c.benefit);
    EXPECT_EQ(items[i].choices[std::size_t(all.choice[i])].benefit, best);
  }
  EXPECT_EQ(greedy_knapsack(items, INFINITY).benefit, all.benefit);
}

TEST(Knapsack, EmptyAndSingleChoice) {
  EXPECT_EQ(optimal_knapsack({}, 1.0).benefit, 0.0);
  const std::vector<KnapsackItem> one{{{{2.0, 3.0}}}};
  EXPECT_EQ(optimal_knapsack(one, 1.0).choice, std::vector<int>{0});
}

// At the walkthrough's size (400 instances x 17 representations): the search
// answers within the budget, never below greedy, under its own bound, and the
// same way twice.
TEST(Knapsack, WalkthroughSizeWithinBudgetAndDeterministic) {
  const auto items = random_items(400, 17, 99);
  const double budget = total_cheapest(items) + 300.0;
  const KnapsackSolution greedy = greedy_knapsack(items, budget);
  const KnapsackSolution opt = optimal_knapsack(items, budget);
  EXPECT_LE(greedy.cost, budget + 1e-9);
  EXPECT_LE(opt.cost, budget + 1e-9);
  EXPECT_GE(opt.benefit, greedy.benefit);
  EXPECT_GE(opt.upper_bound, opt.benefit);
  ASSERT_EQ(opt.choice.size(), items.size());
  EXPECT_EQ(optimal_knapsack(items, budget).choice, opt.choice);
}

}  // namespace
}  // namespace terrasprite
