// SPDX-License-Identifier: MIT
#include "sprite/keyframe_cache.h"

#include <cmath>
#include <glm/glm.hpp>
#include <limits>

namespace terrasprite {

std::unique_ptr<Keyframe> KeyframeCache::take_best(
    const std::function<double(const Keyframe&)>& score) {
  std::size_t best = entries_.size();
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const double s = score(*entries_[i]);
    if (std::isfinite(s) && s < best_score) {
      best_score = s;
      best = i;
    }
  }
  if (best == entries_.size()) return nullptr;
  std::unique_ptr<Keyframe> k = std::move(entries_[best]);
  entries_.erase(entries_.begin() + std::ptrdiff_t(best));
  return k;
}

std::unique_ptr<Keyframe> KeyframeCache::put(std::unique_ptr<Keyframe> k, long long tick,
                                             const Camera& now) {
  if (capacity_ <= 0) return k;
  k->used = tick;
  entries_.push_back(std::move(k));
  if (int(entries_.size()) <= capacity_) return nullptr;
  // Evict one: the least recently used, or the one whose camera is farthest from `now`.
  std::size_t victim = 0;
  for (std::size_t i = 1; i < entries_.size(); ++i) {
    const Keyframe &a = *entries_[i], &b = *entries_[victim];
    const bool worse = policy_ == CachePolicy::kLeastRecentlyUsed
                           ? a.used < b.used
                           : glm::length(a.camera.position - now.position) >
                                 glm::length(b.camera.position - now.position);
    if (worse) victim = i;
  }
  std::unique_ptr<Keyframe> out = std::move(entries_[victim]);
  entries_.erase(entries_.begin() + std::ptrdiff_t(victim));
  return out;
}

}  // namespace terrasprite
