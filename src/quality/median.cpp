// SPDX-License-Identifier: MIT
// Exact median by a bucket pass then a selection inside one bucket: for
// non-negative floats the bit pattern orders like the value, so the top 16 bits
// give monotone buckets. Two linear passes instead of nth_element over a copy
// of a full-HD map (which costs as much as FLIP's filters).
#include "quality/median.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

namespace terrasprite::quality::detail {

namespace {

// -0 and anything below 0 share bucket 0 with +0.
std::uint32_t bucket(float v) { return std::bit_cast<std::uint32_t>(v > 0 ? v : 0.0f) >> 16; }

// The k-th smallest (0-based) of the selected values, given bucket counts.
float select(std::span<const float> values, std::span<const std::uint8_t> mask,
             const std::vector<std::size_t>& counts, std::size_t k) {
  std::uint32_t b = 0;
  while (k >= counts[b]) k -= counts[b++];
  std::vector<float> in_bucket;
  in_bucket.reserve(counts[b]);
  for (std::size_t i = 0; i < values.size(); ++i)
    if ((mask.empty() || mask[i]) && bucket(values[i]) == b) in_bucket.push_back(values[i]);
  std::nth_element(in_bucket.begin(), in_bucket.begin() + static_cast<std::ptrdiff_t>(k), in_bucket.end());
  return in_bucket[k];
}

}  // namespace

double median(std::span<const float> values, std::span<const std::uint8_t> mask) {
  std::vector<std::size_t> counts(1u << 16, 0);
  std::size_t n = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    ++counts[bucket(values[i])];
    ++n;
  }
  if (n == 0) return std::nan("");
  const double hi = select(values, mask, counts, n / 2);
  if (n % 2) return hi;
  return 0.5 * (hi + select(values, mask, counts, n / 2 - 1));
}

}  // namespace terrasprite::quality::detail
