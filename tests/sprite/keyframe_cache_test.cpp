// SPDX-License-Identifier: MIT
// The LOD-sprite keyframe cache: held keyframes never exceed the budget, a
// reused keyframe's error for the view is under the acceptance threshold,
// and flying a path back reuses keyframes from the way out.
#include <gtest/gtest.h>

#include "sprite_test_util.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {
namespace {

using namespace sprite_test;

std::vector<Camera> there_and_back(const Heightfield& h, int frames, double aspect) {
  std::vector<Camera> p = paper_path(h, frames, aspect);
  p.insert(p.end(), p.rbegin(), p.rend());
  return p;
}

struct Flight {
  int keyframes = 0, hits = 0;
};

Flight fly(SpriteRenderer& r, const std::vector<Camera>& path, std::size_t budget) {
  Flight f;
  const SpriteOptions& o = r.options();
  for (const Camera& c : path) {
    const Frame frame = r.draw(c);
    f.keyframes += frame.cls == FrameClass::kKey;
    if (budget > 0) {
      EXPECT_LE(r.keyframe_bytes_held(), budget);
    }
    if (r.last_cache_hit()) {
      ++f.hits;
      EXPECT_EQ(frame.cls, FrameClass::kSprite);
      const SpriteError e = r.error(c);  // against the reused keyframe
      EXPECT_LE(e.value(o.metric), o.cache_accept * o.threshold_px);
      EXPECT_FALSE(r.trigger_for(e).has_value());
    }
  }
  return f;
}

TEST(KeyframeCache, StaysWithinBudgetAndReusesUnderThreshold) {
  GlContext gl;
  Terrain t = small_mountains();
  Scene scene(t);
  const int w = 96, h = 72;
  const std::size_t one = std::size_t(w) * h * 8;
  const std::vector<Camera> path = there_and_back(t.heights, 60, double(w) / h);
  int without = 0;
  {
    SpriteRenderer r(scene, w, h, {});
    without = fly(r, path, 0).keyframes;
  }
  for (CachePolicy policy : {CachePolicy::kLeastRecentlyUsed, CachePolicy::kFarthest}) {
    SpriteRenderer small(scene, w, h, {.cache_bytes = 3 * one + 100, .cache_policy = policy});
    const Flight f = fly(small, path, 3 * one + 100);
    EXPECT_LE(small.cached_keyframes(), 2) << to_string(policy);
    EXPECT_LE(f.keyframes, without) << to_string(policy);
  }
  SpriteRenderer big(scene, w, h, {.cache_bytes = 256u << 20});
  const Flight f = fly(big, path, 256u << 20);
  EXPECT_GT(f.hits, 0);
  EXPECT_LT(f.keyframes, without);  // the way back reuses the way out
  big.reset();
  EXPECT_EQ(big.cached_keyframes(), 0);
}

TEST(KeyframeCache, RejectsABadAcceptance) {
  GlContext gl;
  Terrain t = small_mountains();
  Scene scene(t);
  EXPECT_THROW(SpriteRenderer(scene, 32, 32, {.cache_accept = 0}), InputError);
  EXPECT_THROW(SpriteRenderer(scene, 32, 32, {.cache_accept = 1.5}), InputError);
}

}  // namespace
}  // namespace terrasprite
