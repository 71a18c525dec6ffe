// SPDX-License-Identifier: MIT
// The warp schedule over the voxel renderer: drawing into a reused frame
// (draw_into) gives the frames a fresh draw() gives, bit for bit, and a real
// frame is the central crop of the margin render, as warping it back to its
// own camera returns.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "terrasprite/warp/warp.h"
#include "terrasprite/warp/warp_renderer.h"

namespace terrasprite {
namespace {

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

struct Fixture {
  Terrain terrain;
  VoxelTerrain voxels;
  static Terrain make() {
    TerrainOptions to;
    to.synthetic_size = 65;
    to.erosion_passes = 0;
    return load_terrain(to);
  }
  Fixture() : terrain(make()), voxels(terrain) {}
  Camera camera(int i, int w, int h) const {
    const double E = terrain.heights.extent();
    Camera c;
    c.position = {0.02 * E * i, -0.5 * E + 0.03 * E * i, terrain.heights.max_height() + 0.1 * E};
    c.yaw_deg = 1.5 * i;
    c.pitch_deg = -20 - 2.0 * i;
    c.fov_y_deg = 60;
    c.aspect = double(w) / h;
    fit_clip_planes(c, terrain.heights);
    return c;
  }
};

constexpr int W = 96, H = 54, M = 8;

TEST(WarpSchedule, VoxelDrawIntoAReusedFrameMatchesDraw) {
  const Fixture fx;
  VoxelOptions o;
  o.threads = 2;
  VoxelRenderer r(fx.voxels, W, H, o);
  Frame reused;
  reused.color = Image(W, H);
  std::memset(reused.color.rgba.data(), 0x5a, reused.color.rgba.size());  // stale pixels
  reused.depth.assign(std::size_t(W) * H, 1.0f);
  for (int i = 0; i < 3; ++i) {
    const Frame fresh = r.draw(fx.camera(i, W, H));
    r.draw_into(fx.camera(i, W, H), reused);
    EXPECT_EQ(reused.color.rgba, fresh.color.rgba) << i;
    EXPECT_TRUE(same_bits(reused.depth, fresh.depth)) << i;
    EXPECT_EQ(reused.cls, FrameClass::kVoxel);
    EXPECT_EQ(reused.width(), W);
  }
}

TEST(WarpSchedule, ReusedFramesMatchFreshOnesAndRealFramesAreTheCrop) {
  const Fixture fx;
  VoxelOptions o;
  o.threads = 2;
  for (WarpMethod method : {WarpMethod::kPoly2, WarpMethod::kDepth}) {
    VoxelRenderer big_a(fx.voxels, W + 2 * M, H + 2 * M, o),
        big_b(fx.voxels, W + 2 * M, H + 2 * M, o);
    WarpScheduleOptions so;
    so.real_every = 3;
    so.margin_x = so.margin_y = M;
    so.warp.method = method;
    WarpScheduler fresh_sched(big_a, W, H, so), reused_sched(big_b, W, H, so);
    Frame reused;  // handed back every time, as the experiment loop does
    for (int i = 0; i < 8; ++i) {
      const Camera c = fx.camera(i, W, H);
      const Frame fresh = fresh_sched.draw(c);
      reused_sched.draw_into(c, reused);
      const std::string what = fmt::format("{} frame {}", to_string(method), i);
      EXPECT_EQ(reused.color.rgba, fresh.color.rgba) << what;
      EXPECT_TRUE(same_bits(reused.depth, fresh.depth)) << what;
      EXPECT_EQ(reused.cls, fresh.cls) << what;
      EXPECT_EQ(reused.cls, i % 3 == 0 ? FrameClass::kVoxel : FrameClass::kWarp) << what;
      if (i % 3 != 0) continue;
      // A real frame: the margin render warped back to its own camera.
      const Frame real = big_a.render(with_margin(c, W, H, M, M));
      WarpOptions crop;
      crop.method = WarpMethod::kPoly2;
      const WarpedFrame back = warp_frame(real, c, W, H, crop);
      EXPECT_EQ(fresh.color.rgba, back.frame.color.rgba) << what;
      EXPECT_TRUE(same_bits(fresh.depth, back.frame.depth)) << what;
    }
  }
}

}  // namespace
}  // namespace terrasprite
