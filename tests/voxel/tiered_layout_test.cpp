// SPDX-License-Identifier: MIT
// The tiered polar plane layout: near the vertical vanishing point
// only every s-th column is sampled. Every pixel must still find both of its
// columns' samples, the layout must save samples where V is in view, and the
// straight-down view must stay as close to the supersampled reference as the
// untiered layout was.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "terrasprite/quality/quality.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "voxel/locate_row.h"
#include "voxel/vertical_planes.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {
namespace {

Camera view_camera(double pitch, double roll, int w, int h) {
  Camera c;
  c.position = {10.0, -20.0, 500.0};
  c.pitch_deg = pitch;
  c.roll_deg = roll;
  c.yaw_deg = 30;
  c.fov_y_deg = 60;
  c.aspect = double(w) / h;
  return c;
}

TEST(TieredLayout, EveryPixelFindsBothColumnsSamples) {
  struct View {
    double pitch, roll;
    int w, h;
  };
  for (View v : {View{-90, 0, 320, 180}, View{-90, 25, 203, 117}, View{-60, 0, 320, 180},
                 View{-45, 15, 160, 90}, View{-30, 0, 320, 180}, View{-75, -40, 257, 191}}) {
    const PlaneLayout L = make_plane_layout(view_camera(v.pitch, v.roll, v.w, v.h), v.w, v.h, 1.0);
    ASSERT_TRUE(L.polar) << v.pitch;
    const int n = L.columns;
    if (L.wrap) {
      EXPECT_EQ(n % L.smax, 0) << v.pitch;
    } else {
      EXPECT_EQ((n - 1) % L.smax, 0) << v.pitch;
    }
    std::vector<std::int64_t> k0(n), k1(n);
    std::int64_t samples = 0;
    for (int c = 0; c < n; ++c) {
      std::int64_t a = 0, b = -1;
      if (!L.rows(c, v.w, v.h, a, b)) b = -1;
      k0[c] = std::max(a, L.tier_start(c));
      k1[c] = b;
      samples += std::max<std::int64_t>(0, k1[c] - k0[c] + 1);
    }
    int missing = 0;
    for (int y = 0; y < v.h; ++y)
      for (int x = 0; x < v.w; ++x) {
        double cf, kf;
        L.locate(x + 0.5, y + 0.5, cf, kf);
        const int s = L.stride_at(kf);
        ASSERT_TRUE(s >= 1 && s <= L.smax && (s & (s - 1)) == 0);
        const std::int64_t left = floor_i64(cf / s) * s, kb = floor_i64(kf);
        for (std::int64_t c : {left, left + s}) {
          if (L.wrap) c = (c % n + n) % n;
          if (c < 0 || c >= n) continue;  // beyond the outermost columns (at most half a column)
          ASSERT_EQ(c % s, 0);
          missing += kb < k0[c] || kb + 1 > k1[c];
        }
      }
    EXPECT_EQ(missing, 0) << "pitch " << v.pitch << " roll " << v.roll;
    if (L.wrap) {
      // V in view: the fine columns alone would put several samples on each
      // central pixel; the tiers keep the buffer near the pixel count.
      EXPECT_GE(L.smax, 8) << v.pitch;
      EXPECT_LT(double(samples), 2.2 * v.w * v.h) << "pitch " << v.pitch;
    }
  }
}

// The resample's vectorised polar locate (rational atan) against the layout's
// scalar one (libm atan2), over whole rows, V inside and outside the image.
TEST(TieredLayout, RowLocateMatchesTheScalarLocate) {
  for (double pitch : {-90.0, -70.0, -40.0}) {
    const int W = 301, H = 170;
    const PlaneLayout L = make_plane_layout(view_camera(pitch, 10, W, H), W, H, 1.0);
    ASSERT_TRUE(L.polar);
    const PolarRowLocator row{L.vx, L.vy, L.ex, L.ey, L.c0, 1.0 / L.dc, 1.0 / L.dr, L.wrap};
    std::vector<double> cf(W), kf(W);
    double worst_c = 0, worst_k = 0;
    for (int y = 0; y < H; ++y) {
      locate_polar_row(row, y, 0, W, cf.data(), kf.data());
      for (int x = 0; x < W; ++x) {
        double c, k;
        L.locate(x + 0.5, y + 0.5, c, k);
        // Angles next to 0 may land on either side of the wrap.
        const double dc = std::abs(c - cf[x]);
        worst_c = std::max(worst_c, L.wrap ? std::min(dc, std::abs(dc - L.columns)) : dc);
        worst_k = std::max(worst_k, std::abs(k - kf[x]));
      }
    }
    EXPECT_LT(worst_c, 1e-8) << "pitch " << pitch;
    EXPECT_LT(worst_k, 1e-8) << "pitch " << pitch;
  }
}

TEST(TieredLayout, StraightDownStaysCloseToTheReference) {
  TerrainOptions to;
  to.synthetic_size = 129;
  const Terrain t = load_terrain(to);
  const VoxelTerrain vt(t);
  const int W = 192, H = 108;
  const double E = t.heights.extent();
  Camera c;
  c.position = {0.0, -0.25 * E, double(t.heights.max_height()) + 0.15 * E};
  c.pitch_deg = -90;
  c.fov_y_deg = 60;
  c.aspect = double(W) / H;
  fit_clip_planes(c, t.heights);
  VoxelOptions o;
  o.threads = 2;
  VoxelRenderer r(vt, W, H, o);
  ReferenceOptions ro;
  ro.threads = 2;
  VoxelReference ref(vt, W, H, ro);
  const double s = quality::ssim(ref.render(c).color.view(), r.render(c).color.view()).ssim;
  // 0.99570 untiered, 0.99569 tiered (480x270, 513^2 terrain: 0.99863 and 0.99865).
  EXPECT_GE(s, 0.99) << "SSIM against the reference";
}

}  // namespace
}  // namespace terrasprite
