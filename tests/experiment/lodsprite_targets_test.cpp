// SPDX-License-Identifier: MIT
// The LOD-sprite result's targets and keyframe triggers, on results built by
// hand: a target reads met or missed only where its measurement means
// something. No GL; well under a second.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "terrasprite/experiment/lodsprite/lodsprite_result.h"
#include "terrasprite/report/lodsprite_json.h"
#include "terrasprite/report/lodsprite_report.h"

namespace terrasprite::lodsprite {
namespace {

LodspriteFrame key(int i, Trigger t, double error, double scale = 1) {
  LodspriteFrame f;
  f.frame = i;
  f.cls = FrameClass::kKey;
  f.trigger = t;
  f.error_px = error;
  f.resample_scale = scale;
  return f;
}

// A run whose every frame was a keyframe: no sprite frame to measure.
LodspriteResult only_keyframes(int frames) {
  LodspriteResult r;
  r.path = "paper";
  r.frames = frames;
  r.sprite.keyframes = frames;
  r.sprite.sprite_frames = 0;
  r.sprite.mean_psnr = r.lod.mean_psnr = 100;
  r.sprite.mean_psnr_sprite_frames = r.lod.mean_psnr_sprite_frames = NAN;
  r.sprite.ssim_above_lod_fraction = 1;
  r.bound = {.f = 1, .r = NAN, .speedup_bound = NAN, .efficiency = NAN};
  for (int i = 0; i < frames; ++i) r.per_frame.push_back(key(i, Trigger::kError, 2.0));
  return r;
}

TEST(LodspriteTargets, NotApplicableWithoutSpriteFramesOrThePapersFrameCount) {
  const LodspriteTargets t = only_keyframes(10).targets();
  for (const TargetCheck* c :
       {&t.keyframes_at_most_28, &t.efficiency_at_least_0_9, &t.ssim_above_lod_on_95pct,
        &t.mean_psnr_above_lod, &t.mean_psnr_above_lod_on_sprite_frames}) {
    EXPECT_EQ(c->state, TargetState::kNotApplicable);
    EXPECT_FALSE(c->why.empty());
  }
  const nlohmann::json j = report::lodsprite_json(only_keyframes(10));
  EXPECT_TRUE(j["targets"]["efficiency_at_least_0_9"].is_null());
  EXPECT_TRUE(j["targets"]["why_not_applicable"].contains("keyframes_at_most_28"));
  EXPECT_TRUE(j["bound"]["r"].is_null());
  EXPECT_TRUE(j["sprite"]["mean_psnr_sprite_frames"].is_null());
  const std::string text = report::lodsprite_summary_text(only_keyframes(10));
  EXPECT_EQ(text.find(" met"), std::string::npos) << text;
  EXPECT_NE(text.find("n/a (no sprite frames"), std::string::npos) << text;
}

TEST(LodspriteTargets, MetOrMissedOnThePapersRunWithSpriteFrames) {
  LodspriteResult r = only_keyframes(460);
  r.sprite.keyframes = 30;
  r.sprite.sprite_frames = 430;
  r.sprite.mean_psnr_sprite_frames = 31;
  r.lod.mean_psnr_sprite_frames = 30;
  r.bound.efficiency = 0.95;
  const LodspriteTargets t = r.targets();
  EXPECT_EQ(t.keyframes_at_most_28.state, TargetState::kMissed);
  EXPECT_EQ(t.efficiency_at_least_0_9.state, TargetState::kMet);
  EXPECT_EQ(t.mean_psnr_above_lod_on_sprite_frames.state, TargetState::kMet);
  r.path = "my_path.json";
  EXPECT_EQ(r.targets().keyframes_at_most_28.state, TargetState::kNotApplicable);
}

TEST(LodspriteTargets, KeyframesAreCountedByTheTriggerThatFiredThem) {
  LodspriteResult r;
  r.threshold_px = 1;
  r.per_frame = {key(0, Trigger::kFirst, 0), key(1, Trigger::kScale, 0.4, 1.3),
                 key(2, Trigger::kScale, 0.5, 1.4), key(3, Trigger::kError, 1.2)};
  LodspriteFrame sprite;
  sprite.cls = FrameClass::kSprite;
  r.per_frame.push_back(sprite);
  const std::vector<KeyframeTriggerRow> rows = r.keyframes_by_trigger();
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].trigger, Trigger::kFirst);
  EXPECT_TRUE(std::isnan(rows[0].measure_median));
  EXPECT_EQ(rows[2].trigger, Trigger::kScale);
  EXPECT_EQ(rows[2].keyframes, 2);
  EXPECT_DOUBLE_EQ(rows[2].error_max, 0.5);
  EXPECT_DOUBLE_EQ(rows[2].measure_max, 1.4);
}

}  // namespace
}  // namespace terrasprite::lodsprite
