// SPDX-License-Identifier: MIT
#include "terrasprite/common/stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace terrasprite {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  auto mid = v.begin() + v.size() / 2;
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2) return *mid;
  double hi = *mid;
  double lo = *std::max_element(v.begin(), mid);
  return 0.5 * (lo + hi);
}

double mean(std::span<const double> v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

namespace {
// Nearest rank in a sorted sample: the ceil(p n / 100)-th smallest, at least the first.
double rank_sorted(const std::vector<double>& sorted, double p) {
  const std::size_t n = sorted.size();
  std::size_t rank = std::size_t(std::ceil(p / 100.0 * double(n) - 1e-9));
  rank = std::clamp<std::size_t>(rank, 1, n);
  return sorted[rank - 1];
}
}  // namespace

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return rank_sorted(v, p);
}

Summary summarize(std::span<const double> values) {
  std::vector<double> v;
  v.reserve(values.size());
  for (double x : values)
    if (std::isfinite(x)) v.push_back(x);
  Summary s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.count = int(v.size());
  s.total = std::accumulate(v.begin(), v.end(), 0.0);
  s.mean = s.total / double(v.size());
  s.median = median(v);
  s.min = v.front();
  s.max = v.back();
  s.p90 = rank_sorted(v, 90);
  s.p95 = rank_sorted(v, 95);
  s.p99 = rank_sorted(v, 99);
  const double lo = rank_sorted(v, 10), hi = s.p90;
  double sum = 0;
  int k = 0;
  for (double x : v)
    if (x >= lo && x <= hi) {
      sum += x;
      ++k;
    }
  s.trimmed_mean = k ? sum / k : s.mean;
  return s;
}

Summary summarize_valid(std::span<const double> values) {
  std::vector<double> v;
  for (double x : values)
    if (x >= 0) v.push_back(x);
  return summarize(v);
}

}  // namespace terrasprite
