// SPDX-License-Identifier: MIT
// The one statistics helper: summaries of per-frame figures.
#pragma once
#include <span>
#include <vector>

namespace terrasprite {

/// Summary of a sample. Percentiles are nearest-rank: the p-th percentile of
/// n values is the ceil(p / 100 * n)-th smallest (p99 of 460 frames is the
/// 456th smallest), so it is always a value that occurred. The median is the
/// usual one (mean of the two middle values for an even count). All fields
/// are 0 for an empty sample.
struct Summary {
  int count = 0;
  double total = 0, mean = 0, median = 0;
  double min = 0, max = 0;
  double p90 = 0, p95 = 0, p99 = 0;
  double trimmed_mean =
      0;  ///< mean of the values between the 10th and 90th percentiles (inclusive)
};

/// Summarises `values`. Values that are not finite are skipped.
Summary summarize(std::span<const double> values);
/// Summarises the values >= 0 only: for timer results where -1 means "no result".
Summary summarize_valid(std::span<const double> values);

/// Nearest-rank percentile of `values` (p in [0, 100]; p = 0 gives the minimum). 0 for none.
double percentile(std::vector<double> values, double p);
/// Median of `values` (0 for none).
double median(std::vector<double> values);
/// Arithmetic mean (0 for none).
double mean(std::span<const double> values);

}  // namespace terrasprite
