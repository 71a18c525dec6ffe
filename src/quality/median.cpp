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
std::uint32_t bucket(float v) {
  return std::bit_cast<std::uint32_t>(v > 0 ? v : 0.0f) >> 16;
}

// The k-th smallest (0-based) of the selected values, given bucket counts,
// and, in `below`, the (k-1)-th (for k > 0): an even count needs both middle
// values, and one scan of the map for the two (rather than one per value)
// saves a full pass. The (k-1)-th is in the same bucket or is the largest of
// the previous non-empty one; after nth_element it is the largest value
// before position k.
float select(std::span<const float> values, std::span<const std::uint8_t> mask,
             const std::vector<std::size_t>& counts, std::size_t k, float* below) {
  std::uint32_t b = 0;
  std::size_t before = 0;  // selected values in buckets below b
  while (k - before >= counts[b]) before += counts[b++];
  std::uint32_t lo = b;
  if (below && k == before)  // k is the first of its bucket: look one bucket lower
    while (counts[--lo] == 0) {
    }
  if (lo != b) before -= counts[lo];
  std::vector<float> in_bucket;
  in_bucket.reserve(counts[b] + (lo != b ? counts[lo] : 0));
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    const std::uint32_t v = bucket(values[i]);
    if (v == b || v == lo) in_bucket.push_back(values[i]);
  }
  const auto kth = in_bucket.begin() + static_cast<std::ptrdiff_t>(k - before);
  std::nth_element(in_bucket.begin(), kth, in_bucket.end());
  if (below) *below = *std::max_element(in_bucket.begin(), kth);
  return *kth;
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
  if (n % 2) return select(values, mask, counts, n / 2, nullptr);
  float lo = 0;
  const double hi = select(values, mask, counts, n / 2, &lo);
  return 0.5 * (hi + lo);
}

}  // namespace terrasprite::quality::detail
