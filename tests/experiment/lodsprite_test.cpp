// SPDX-License-Identifier: MIT
// run_lodsprite() in-process on a tiny setup (65² synthetic terrain, 12
// frames at 64x64): the frame classes, keyframe count, reference frames,
// sweeps and figures it reports agree with each other and with the options.
#include "terrasprite/experiment/lodsprite/lodsprite.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite::lodsprite {
namespace {

Terrain tiny_terrain() {
  TerrainOptions t;
  t.synthetic_size = 65;
  t.resample = 65;
  return load_terrain(t);
}

LodspriteOptions tiny_options() {
  LodspriteOptions o;
  o.frames = 12;
  o.width = o.height = 64;
  o.lod_quads = 4;
  o.flip = false;
  o.thresholds = {1, 4};
  o.frame_counts = {6, 12};
  o.lod_sweep = {4};
  return o;
}

TEST(RunLodsprite, FrameClassesAndKeyframesAgree) {
  const Terrain terrain = tiny_terrain();
  const LodspriteOptions o = tiny_options();
  std::vector<int> saved;
  LodspriteOptions with_hook = o;
  with_hook.on_sprite_frame = [&](int i, const Frame& f) {
    EXPECT_EQ(f.color.width, 64);
    saved.push_back(i);
  };
  const LodspriteResult r = run_lodsprite(with_hook, terrain);

  ASSERT_EQ(r.frames, 12);
  ASSERT_EQ(r.per_frame.size(), 12u);
  EXPECT_EQ(saved.size(), 12u);
  // The first frame has no keyframe to reuse: it is one.
  EXPECT_EQ(r.per_frame[0].cls, FrameClass::kKey);
  EXPECT_TRUE(r.per_frame[0].trigger.has_value());
  const int keys = int(std::count_if(r.per_frame.begin(), r.per_frame.end(),
                                     [](const LodspriteFrame& f) { return f.key(); }));
  EXPECT_EQ(r.sprite.keyframes, keys);
  EXPECT_GE(keys, 1);
  EXPECT_LT(keys, r.frames);  // the path is slow enough for sprite frames

  EXPECT_EQ(r.sprite.keyframes + r.sprite.sprite_frames, r.frames);
  EXPECT_DOUBLE_EQ(r.bound.f, double(keys) / r.frames);
  for (const LodspriteFrame& f : r.per_frame) {
    // A keyframe is drawn from itself; a sprite frame from an earlier keyframe.
    if (f.key())
      EXPECT_EQ(f.keyframe, f.frame);
    else
      EXPECT_LT(f.keyframe, f.frame);
    EXPECT_EQ(f.key(), f.trigger.has_value());
    EXPECT_TRUE(f.reference);
    if (f.key()) {
      EXPECT_DOUBLE_EQ(f.sprite.ssim, 1.0);  // the reference frame itself
    }
    EXPECT_GT(f.sprite.ssim, 0.0);
    EXPECT_LE(f.sprite.ssim, 1.0);
  }
  EXPECT_EQ(r.reference_frames, r.frames);
  EXPECT_GT(r.speedup, 0.0);
}

TEST(RunLodsprite, SweepsAndFiguresFollowTheOptions) {
  const LodspriteResult r = run_lodsprite(tiny_options(), tiny_terrain());
  ASSERT_EQ(r.threshold_sweep.size(), 2u);
  // The main setting is the main run's figures, the other a separate pass.
  EXPECT_EQ(r.threshold_sweep[0].pass.measured_in, SweepMethod::kMainRun);
  EXPECT_EQ(r.threshold_sweep[0].pass.keyframes, r.sprite.keyframes);
  EXPECT_EQ(r.threshold_sweep[1].pass.measured_in, SweepMethod::kSeparatePass);
  // A higher threshold never asks for more keyframes.
  EXPECT_LE(r.threshold_sweep[1].pass.keyframes, r.threshold_sweep[0].pass.keyframes);
  ASSERT_EQ(r.frame_count_sweep.size(), 2u);
  for (const FrameCountPoint& p : r.frame_count_sweep) {
    EXPECT_GE(p.keyframes, 1);
    EXPECT_LE(p.keyframes, p.frames);
  }
  ASSERT_EQ(r.lod_sweep.size(), 1u);
  EXPECT_EQ(r.lod_sweep[0].pass.measured_in, SweepMethod::kMainRun);
  ASSERT_EQ(r.figures.size(), 2u);
  EXPECT_EQ(r.figures[0].name, SameFrameFigure::kFig13);
  EXPECT_EQ(r.figures[0].texture, "checker");
  EXPECT_EQ(r.figures[1].name, SameFrameFigure::kFig14);
  for (const FigureCompare& f : r.figures) {
    EXPECT_FALSE(r.per_frame[std::size_t(f.frame)].key());  // a sprite frame is shown
    EXPECT_EQ(f.sprite_image.width, 64);
    EXPECT_EQ(f.diff_sprite_image.height, 64);
  }
}

TEST(RunLodsprite, ReferenceEveryThirdFrame) {
  LodspriteOptions o = tiny_options();
  o.reference_every = 3;
  o.thresholds.clear();
  o.frame_counts.clear();
  o.lod_sweep.clear();
  const LodspriteResult r = run_lodsprite(o, tiny_terrain());
  EXPECT_EQ(r.reference_frames, 4);  // frames 0, 3, 6, 9
  for (const LodspriteFrame& f : r.per_frame) {
    EXPECT_EQ(f.reference, f.frame % 3 == 0);
    EXPECT_EQ(std::isnan(f.full_ms), !f.reference);
  }
  EXPECT_TRUE(r.threshold_sweep.empty());
}

TEST(RunLodsprite, BadOptionsNameTheOption) {
  LodspriteOptions o = tiny_options();
  o.frames = 0;
  EXPECT_THROW(run_lodsprite(o, tiny_terrain()), InputError);
  EXPECT_THROW(parse_metric("fancy"), InputError);
  EXPECT_THROW(parse_shading("glossy"), InputError);
  EXPECT_EQ(parse_metric("contrast"), ErrorMetric::kContrast);
  EXPECT_STREQ(frame_class_name(FrameClass::kKey), "key");
}

}  // namespace
}  // namespace terrasprite::lodsprite
