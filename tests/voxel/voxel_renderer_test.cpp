// SPDX-License-Identifier: MIT
// Correctness of the voxel ray caster: analytic depth on a flat plane, the
// horizon, occlusion by a spike, coherent traversal against per-pixel
// marching under pitch and roll, agreement with the GL renderer, edge cases.
#include "terrasprite/voxel/voxel_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {
namespace {

Terrain flat_terrain(int n, double spacing, float z) {
  Terrain t;
  t.heights.width = t.heights.height = n;
  t.heights.spacing_x = t.heights.spacing_y = spacing;
  t.heights.heights.assign(std::size_t(n) * n, z);
  t.texture = Image(8, 8);
  for (std::size_t i = 0; i < t.texture.rgba.size(); i += 4) {
    t.texture.rgba[i] = 90;
    t.texture.rgba[i + 1] = 140;
    t.texture.rgba[i + 2] = 60;
    t.texture.rgba[i + 3] = 255;
  }
  return t;
}

Camera make_camera(glm::dvec3 pos, double yaw, double pitch, double roll, int w, int h) {
  Camera c;
  c.position = pos;
  c.yaw_deg = yaw;
  c.pitch_deg = pitch;
  c.roll_deg = roll;
  c.fov_y_deg = 60;
  c.aspect = double(w) / h;
  return c;
}

bool is_sky(const Frame& f, int x, int y) {
  const std::uint8_t* p = f.color.px(x, y);
  return p[0] == kSkyColor[0] && p[1] == kSkyColor[1] && p[2] == kSkyColor[2];
}

const VoxelVariant kAll[] = {VoxelVariant::kNaive, VoxelVariant::kCoherent,
                             VoxelVariant::kMultires};

Frame render(const VoxelTerrain& vt, const Camera& c, int w, int h, VoxelVariant v,
             double ratio = 1.0) {
  VoxelOptions o;
  o.variant = v;
  o.threads = 2;
  o.pixel_voxel_ratio = ratio;
  VoxelRenderer r(vt, w, h, o);
  return r.render(c);
}

TEST(VoxelRenderer, FlatPlaneDepthIsAnalytic) {
  const int W = 64, H = 48;
  Terrain t = flat_terrain(129, 10.0, 100.0f);  // 1280 m square
  VoxelTerrain vt(t);
  for (double roll : {0.0, 25.0})
    for (double pitch : {-30.0, -60.0, -90.0}) {
      Camera c = make_camera({0, -100, 400}, 20, pitch, roll, W, H);
      for (VoxelVariant v : kAll) {
        Frame f = render(vt, c, W, H, v);
        int checked = 0;
        for (int y = 0; y < H; ++y)
          for (int x = 0; x < W; ++x) {
            glm::dvec3 d = c.ray_direction(x + 0.5, y + 0.5, W, H);
            if (d.z >= 0) continue;
            double s = (100.0 - 400.0) / d.z;
            glm::dvec3 p = c.position + s * d;
            if (std::abs(p.x) > 600 || std::abs(p.y) > 600)
              continue;  // off the plane or near its edge
            double expect = s * glm::dot(d, c.forward());
            EXPECT_NEAR(f.depth[std::size_t(y) * W + x], expect, 0.01 * expect + 1.0)
                << to_string(v) << " pitch " << pitch << " roll " << roll << " at " << x << ","
                << y;
            ++checked;
          }
        EXPECT_GT(checked, W * H / 4) << "pitch " << pitch;
      }
    }
}

TEST(VoxelRenderer, HorizonRowIsAnalytic) {
  const int W = 64, H = 48;
  Terrain t =
      flat_terrain(1025, 100.0, 0.0f);  // 102 km: its far edge lies within a pixel of the horizon
  VoxelTerrain vt(t);
  for (double pitch : {0.0, -10.0}) {
    Camera c = make_camera({0, 0, 10}, 0, pitch, 0, W, H);
    const double fy = H / (2.0 * std::tan(30.0 * 3.14159265358979323846 / 180.0));
    const double y_horizon = H / 2.0 - fy * std::tan(-pitch * 3.14159265358979323846 / 180.0);
    const int first_ground =
        int(std::ceil(y_horizon - 0.5));  // first row whose centre is below the horizon
    for (VoxelVariant v : kAll) {
      Frame f = render(vt, c, W, H, v);
      for (int x = 0; x < W; x += 7) {
        int y = 0;
        while (y < H && is_sky(f, x, y)) ++y;
        EXPECT_NEAR(y, first_ground, 1) << to_string(v) << " pitch " << pitch << " column " << x;
        for (int yy = y; yy < H; ++yy)
          EXPECT_FALSE(is_sky(f, x, yy)) << to_string(v) << " hole at " << x << "," << yy;
      }
    }
  }
}

TEST(VoxelRenderer, SpikeOccludesExactlyItsPixels) {
  const int W = 96, H = 64;
  Terrain t = flat_terrain(65, 10.0, 0.0f);
  t.heights.at(32, 32) = 200.0f;  // a one-sample spike at the origin: a 20 m wide tent
  VoxelTerrain vt(t);
  Camera c = make_camera({0, -200, 60}, 0, -5, 0, W, H);
  ReferenceOptions ro;
  ro.supersample = 1;
  Frame ref = VoxelReference(vt, W, H, ro).render(c);
  auto spike_mask = [&](const Frame& f) {
    std::vector<char> m(std::size_t(W) * H, 0);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        glm::dvec3 d = c.ray_direction(x + 0.5, y + 0.5, W, H);
        double ground = d.z < 0 ? -60.0 / d.z * glm::dot(d, c.forward()) : INFINITY;
        float z = f.depth[std::size_t(y) * W + x];
        m[std::size_t(y) * W + x] = std::isfinite(z) && z < ground - 5.0;
      }
    return m;
  };
  auto truth = spike_mask(ref);
  int n_truth = 0;
  for (char b : truth) n_truth += b;
  ASSERT_GT(n_truth, 50);
  for (VoxelVariant v : kAll) {
    auto m = spike_mask(render(vt, c, W, H, v));
    // Resampling the vertical planes may move a silhouette by up to a pixel;
    // any other difference is an occlusion error.
    int diff = 0, gross = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t i = std::size_t(y) * W + x;
        if (m[i] == truth[i]) continue;
        ++diff;
        bool near_edge = false;
        for (int b = -1; b <= 1; ++b)
          for (int a = -1; a <= 1; ++a) {
            int xx = std::clamp(x + a, 0, W - 1), yy = std::clamp(y + b, 0, H - 1);
            near_edge = near_edge || truth[std::size_t(yy) * W + xx] != truth[i];
          }
        gross += !near_edge;
      }
    EXPECT_EQ(gross, 0) << to_string(v)
                        << ": spike pixels away from its silhouette differ from the exact surface";
    EXPECT_LE(diff, n_truth / 3) << to_string(v);
  }
}

// Synthetic terrain plus a thin peak one sample wide.
Terrain peaked_terrain() {
  TerrainOptions o;
  o.synthetic_size = 129;
  o.erosion_passes = 0;
  Terrain t = load_terrain(o);
  t.heights.at(64, 40) += 1500.0f;
  return t;
}

struct Diff {
  double mean_abs = 0;
  double bad_fraction = 0;  // pixels off by more than 48 levels in a channel
};
Diff compare(const Frame& a, const Frame& b) {
  Diff d;
  const std::size_t n = std::size_t(a.width()) * a.height();
  for (std::size_t i = 0; i < n; ++i) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      int e = std::abs(int(a.color.rgba[i * 4 + c]) - int(b.color.rgba[i * 4 + c]));
      d.mean_abs += e;
      worst = std::max(worst, e);
    }
    d.bad_fraction += worst > 48;
  }
  d.mean_abs /= 3.0 * n;
  d.bad_fraction /= n;
  return d;
}

TEST(VoxelRenderer, CoherentMatchesNaiveUnderPitchAndRoll) {
  const int W = 120, H = 80;
  Terrain t = peaked_terrain();
  VoxelTerrain vt(t);
  Terrain plain = t;
  plain.heights.at(64, 40) -= 1500.0f;
  VoxelTerrain vplain(plain);
  // The peak's top, and a point 300 m below it that every view looks at from 1 km.
  const glm::dvec3 peak(t.heights.world_x(64), t.heights.world_y(40), t.heights.at(64, 40));
  struct View {
    double pitch, roll;
  };
  for (View view :
       {View{0, 0}, View{-30, 0}, View{-60, 0}, View{-90, 0}, View{-30, 30}, View{-60, -40}}) {
    Camera c = make_camera({0, 0, 0}, 15, view.pitch, view.roll, W, H);
    c.position = peak - glm::dvec3(0, 0, 300) - 1000.0 * c.forward();
    Frame naive = render(vt, c, W, H, VoxelVariant::kNaive);
    Frame coherent = render(vt, c, W, H, VoxelVariant::kCoherent);
    Diff d = compare(naive, coherent);
    EXPECT_LT(d.mean_abs, 6.0) << "pitch " << view.pitch << " roll " << view.roll;
    EXPECT_LT(d.bad_fraction, 0.03) << "pitch " << view.pitch << " roll " << view.roll;
    // The thin peak: pixels whose depth it changes, naive against coherent.
    Frame naive_plain = render(vplain, c, W, H, VoxelVariant::kNaive);
    Frame coherent_plain = render(vplain, c, W, H, VoxelVariant::kCoherent);
    int peak_naive = 0, peak_both = 0;
    for (std::size_t i = 0; i < naive.depth.size(); ++i) {
      bool a = naive.depth[i] < naive_plain.depth[i] - 20.0f;
      bool b = coherent.depth[i] < coherent_plain.depth[i] - 20.0f;
      peak_naive += a;
      peak_both += a && b;
    }
    EXPECT_GT(peak_naive, 3) << "the peak should be in view, pitch " << view.pitch;
    // Most of the peak survives; resampling may shave a pixel off its outline.
    EXPECT_GE(peak_both, 0.7 * peak_naive)
        << "coherent misses the thin peak, pitch " << view.pitch << " roll " << view.roll;
  }
}

TEST(VoxelRenderer, MultiresStaysCloseToOneLevel) {
  const int W = 160, H = 90;
  Terrain t = peaked_terrain();
  VoxelTerrain vt(t);
  Camera c = make_camera({0, -0.6 * t.heights.extent(), 2500}, 0, -20, 0, W, H);
  Frame one = render(vt, c, W, H, VoxelVariant::kCoherent);
  Frame multi = render(vt, c, W, H, VoxelVariant::kMultires);
  const double s = quality::ssim(one.color.view(), multi.color.view()).ssim;
  EXPECT_GT(s, 0.8);
}

TEST(VoxelRenderer, MatchesGlFullResolution) {
  std::unique_ptr<GlContext> gl;
  try {
    gl = std::make_unique<GlContext>();
  } catch (const DeviceError& e) {
    GTEST_SKIP() << "no GL device: " << e.what();
  }
  const int W = 160, H = 120;
  TerrainOptions o;
  o.synthetic_size = 257;
  Terrain t = load_terrain(o);
  const double E = t.heights.extent();
  Scene scene(t);
  MeshRenderer full(scene, W, H, 0);
  VoxelTerrain vt(t);
  VoxelRenderer voxel(vt, W, H);
  for (double pitch : {-20.0, -45.0}) {
    Camera c =
        make_camera({0.1 * E, -0.9 * E, t.heights.max_height() + 0.25 * E}, 10, pitch, 0, W, H);
    fit_clip_planes(c, t.heights);
    Frame a = full.render(c);
    Frame b = voxel.render(c);
    const double s = quality::ssim(a.color.view(), b.color.view()).ssim;
    // Bound: the mesh is triangulated, the voxel surface bilinear, and the
    // colour maps are filtered differently (GL: trilinear + anisotropic).
    EXPECT_GT(s, 0.9) << "pitch " << pitch;  // measured 0.96 (Wang SSIM, 160x120)
    std::printf("voxel vs GL full resolution, pitch %.0f: SSIM %.4f\n", pitch, s);
  }
}

TEST(VoxelRenderer, EdgeCasesGiveSensibleImages) {
  const int W = 40, H = 30;
  Terrain t = flat_terrain(33, 10.0, 50.0f);
  VoxelTerrain vt(t);
  for (VoxelVariant v : kAll) {
    // Straight down: the centre sees the ground at the analytic distance.
    Frame down = render(vt, make_camera({0, 0, 250}, 0, -90, 0, W, H), W, H, v);
    EXPECT_NEAR(down.depth[std::size_t(H / 2) * W + W / 2], 200.0, 2.0) << to_string(v);
    EXPECT_FALSE(is_sky(down, W / 2, H / 2));
    // Looking up: only sky.
    Frame up = render(vt, make_camera({0, 0, 250}, 0, 45, 0, W, H), W, H, v);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        ASSERT_TRUE(is_sky(up, x, y) && std::isinf(up.depth[std::size_t(y) * W + x]));
    // Below the surface: ground colour, finite depth, no NaN.
    Frame below = render(vt, make_camera({0, 0, 20}, 0, -10, 0, W, H), W, H, v);
    for (float z : below.depth) EXPECT_FALSE(std::isnan(z));
    EXPECT_FALSE(is_sky(below, W / 2, H - 1));
  }
  for (int n : {1, 2}) {
    Terrain tiny = flat_terrain(n, 100.0, 0.0f);
    VoxelTerrain vtiny(tiny);
    for (VoxelVariant v : kAll) {
      Frame f = render(vtiny, make_camera({0, 0, 100}, 0, -90, 0, W, H), W, H, v);
      ASSERT_EQ(f.depth.size(), std::size_t(W) * H);
      for (float z : f.depth) ASSERT_FALSE(std::isnan(z));
      if (n == 1) {
        EXPECT_TRUE(is_sky(f, W / 2, H / 2));  // no area: nothing to hit
      } else {
        EXPECT_FALSE(is_sky(f, W / 2, H / 2));
      }
    }
    Frame ref = VoxelReference(vtiny, W, H).render(make_camera({0, 0, 100}, 0, -90, 0, W, H));
    ASSERT_EQ(ref.depth.size(), std::size_t(W) * H);
    EXPECT_EQ(is_sky(ref, W / 2, H / 2), n == 1);
  }
}

TEST(VoxelRenderer, RejectsBadOptions) {
  Terrain t = flat_terrain(5, 1.0, 0.0f);
  VoxelTerrain vt(t);
  VoxelOptions o;
  o.pixel_voxel_ratio = 0;
  EXPECT_THROW(VoxelRenderer(vt, 10, 10, o), InputError);
  EXPECT_THROW(VoxelRenderer(vt, 0, 10), InputError);
  EXPECT_THROW(parse_voxel_variant("fast"), InputError);
  EXPECT_EQ(parse_voxel_variant("coherent"), VoxelVariant::kCoherent);
}

}  // namespace
}  // namespace terrasprite
