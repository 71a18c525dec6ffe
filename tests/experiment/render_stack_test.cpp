// SPDX-License-Identifier: MIT
// Render modes named in one place, and the voxel + warp stack assembled
// once: sizes, margins and the frames it returns (CPU only, no GL).
#include "terrasprite/experiment/render_stack.h"

#include <gtest/gtest.h>

#include "experiment_test_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/render_mode.h"
#include "terrasprite/experiment/render_run.h"

namespace terrasprite {
namespace {

TEST(RenderMode, EveryNameParsesBackToItsMode) {
  EXPECT_EQ(render_mode_names(), (std::vector<std::string>{"full", "lod", "sprite", "voxel"}));
  for (RenderMode m : kRenderModes) EXPECT_EQ(parse_render_mode(to_string(m)), m);
  try {
    parse_render_mode("raster", "--mode");
    FAIL() << "accepted an unknown mode";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--mode raster: unknown mode");
  }
}

Terrain tiny_terrain() {
  return tiny_synthetic_terrain(33);
}

Camera overview(const Terrain& t, double aspect) {
  const double e = t.heights.extent();
  Camera c = Camera::look_at({0, -0.5 * e, t.heights.max_height() + 0.2 * e},
                             {0, 0, t.heights.min_height()}, 60.0, aspect);
  fit_clip_planes(c, t.heights);
  return c;
}

TEST(RenderStack, VoxelAloneDrawsAtTheOutputSize) {
  const Terrain t = tiny_terrain();
  RenderStackOptions o;
  o.mode = RenderMode::kVoxel;
  o.width = 40;
  o.height = 30;
  RenderStack s = make_render_stack(t, o);
  EXPECT_FALSE(s.warp);
  EXPECT_FALSE(s.gl);
  ASSERT_TRUE(s.voxel);
  EXPECT_EQ(s.margin_x, 0);
  const Frame f = s.renderer().render(overview(t, 40.0 / 30), ReadBack::kColor);
  EXPECT_EQ(f.color.width, 40);
  EXPECT_EQ(f.color.height, 30);
  EXPECT_EQ(f.cls, FrameClass::kVoxel);
}

TEST(RenderStack, VoxelWithAWarpDrawsRealFramesWithTheMarginAndWarpsBetween) {
  const Terrain t = tiny_terrain();
  const VoxelTerrain shared(t);
  RenderStackOptions o;
  o.mode = RenderMode::kVoxel;
  o.width = 40;
  o.height = 30;
  o.voxels = &shared;
  o.warp = WarpMethod::kPoly2;
  o.real_every = 3;
  RenderStack s = make_render_stack(t, o);
  EXPECT_FALSE(s.voxel);     // the shared pyramids are used
  EXPECT_EQ(s.margin_x, 2);  // 0.05 x 40
  EXPECT_EQ(s.margin_y, 2);  // 0.05 x 30 = 1.5, rounded away from zero
  ASSERT_TRUE(s.warp);
  const Camera c = overview(t, 40.0 / 30);
  std::vector<FrameClass> classes;
  for (int i = 0; i < 4; ++i) {
    const Frame f = s.renderer().render(c, ReadBack::kColor);
    EXPECT_EQ(f.color.width, 40);
    EXPECT_EQ(f.color.height, 30);
    classes.push_back(f.cls);
  }
  EXPECT_EQ(classes, (std::vector<FrameClass>{FrameClass::kVoxel, FrameClass::kWarp,
                                              FrameClass::kWarp, FrameClass::kVoxel}));
}

TEST(RenderStack, AWarpMarginOutOfRangeIsRefused) {
  const Terrain t = tiny_terrain();
  RenderStackOptions o;
  o.mode = RenderMode::kVoxel;
  o.warp = WarpMethod::kDepth;
  o.warp_margin = 1.5;
  EXPECT_THROW(make_render_stack(t, o), InputError);
}

TEST(RenderRun, NumbersFramesFromTheRangeStartAndSamplesMemoryEveryN) {
  const Terrain t = tiny_terrain();
  RenderStackOptions so;
  so.mode = RenderMode::kVoxel;
  so.width = 24;
  so.height = 16;
  so.warp = WarpMethod::kPoly2;
  so.real_every = 2;
  RenderStack s = make_render_stack(t, so);
  const std::vector<Camera> path(5, overview(t, 24.0 / 16));
  RenderRunOptions o;
  o.first_frame = 3;
  o.memory_every = 2;
  o.heap_trim = false;
  std::vector<int> handed;
  o.on_frame = [&](int i, const Frame& f) {
    EXPECT_EQ(f.color.width, 24);
    handed.push_back(i);
  };
  const RenderRunResult r = run_render(s.renderer(), path, o);
  EXPECT_EQ(handed, (std::vector<int>{3, 4, 5, 6, 7}));
  ASSERT_EQ(r.frames.size(), 5u);
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    EXPECT_EQ(r.frames[i].frame, int(i) + 3);
    EXPECT_EQ(r.frames[i].cls, i % 2 ? FrameClass::kWarp : FrameClass::kVoxel);
  }
  ASSERT_EQ(r.memory.samples.size(), 3u);  // at 0, 2 and 4 frames drawn
  EXPECT_EQ(r.memory.samples[2].first, 4);
  EXPECT_EQ(r.memory.trim_ms, 0.0);
}

}  // namespace
}  // namespace terrasprite
