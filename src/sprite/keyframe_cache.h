// SPDX-License-Identifier: MIT
// Past LOD-sprite keyframes kept within a memory budget (the future work of
// Chen et al. 1999): when a keyframe is due, a cached one whose error for the
// current view passes the triggers is reused instead of rendering a new one.
#pragma once
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "sprite/keyframe.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite {

class KeyframeCache {
 public:
  /// `capacity`: keyframes kept besides the renderer's current one (0 = off).
  KeyframeCache(int capacity, CachePolicy policy) : capacity_(capacity), policy_(policy) {}
  int capacity() const { return capacity_; }
  int size() const { return int(entries_.size()); }
  void clear() { entries_.clear(); }
  /// The cached keyframe with the smallest `score` among those `score` accepts
  /// (a finite score), removed from the cache; null when none is accepted.
  std::unique_ptr<Keyframe> take_best(const std::function<double(const Keyframe&)>& score);
  /// Keeps `k` (stamped `tick`), evicting by the policy when full; returns the
  /// evicted keyframe (its textures can be reused) or null. With capacity 0
  /// `k` itself comes back.
  std::unique_ptr<Keyframe> put(std::unique_ptr<Keyframe> k, long long tick, const Camera& now);

 private:
  int capacity_;
  CachePolicy policy_;
  std::vector<std::unique_ptr<Keyframe>> entries_;
};

}  // namespace terrasprite
