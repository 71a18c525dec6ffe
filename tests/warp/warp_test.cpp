// SPDX-License-Identifier: MIT
// The post-render warps on scenes rendered analytically (a textured ground
// plane, optionally with a tall box in front): pure rotation, a camera that
// does not move, sideways translation over a plane, disocclusion behind a
// spike, and a voxel-rendered frame.
#include "terrasprite/warp/warp.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <tuple>

#include "terrasprite/camera/renderer.h"
#include "terrasprite/common/error.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "warp/bilinear.h"

namespace terrasprite {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Ground z = 0 with a smooth colour pattern (tens of pixels per period),
// and optionally a box [-s, s]^2 x [0, height] of flat colour.
struct Scene {
  double box_half = 0, box_height = 0;
  double period = 1.0;  // scales the pattern's wavelengths

  // Nearest hit along ray o + t d (t > 0); false for sky.
  bool hit(const glm::dvec3& o, const glm::dvec3& d, glm::dvec3& p, bool& on_box) const {
    double best = std::numeric_limits<double>::infinity();
    on_box = false;
    if (d.z < -1e-9) best = -o.z / d.z;
    if (box_half > 0) {
      // Slab intersection with the box.
      double t0 = 0, t1 = best;
      const double lo[3] = {-box_half, -box_half, 0}, hi[3] = {box_half, box_half, box_height};
      bool ok = true;
      for (int a = 0; a < 3 && ok; ++a) {
        if (std::abs(d[a]) < 1e-12) {
          ok = o[a] >= lo[a] && o[a] <= hi[a];
          continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        ok = t0 <= t1;
      }
      if (ok && t0 > 0 && t0 < best) {
        best = t0;
        on_box = true;
      }
    }
    if (!std::isfinite(best)) return false;
    p = o + best * d;
    return true;
  }
  void ground_color(const glm::dvec3& p, std::uint8_t* c) const {
    const double fade = std::exp(-std::hypot(p.x, p.y) / 3000.0), s = period;
    c[0] = std::uint8_t(120 + 60 * fade * std::sin(p.x / (40.0 * s)));
    c[1] = std::uint8_t(130 + 60 * fade * std::cos(p.y / (55.0 * s)));
    c[2] = std::uint8_t(90 + 40 * fade * std::sin((p.x + p.y) / (70.0 * s)));
    c[3] = 255;
  }

  Frame render(const Camera& cam, int w, int h) const {
    Frame f;
    f.color = Image(w, h);
    f.depth.assign(std::size_t(w) * h, Frame::kSky);
    f.camera = cam;
    const glm::dvec3 fwd = cam.forward();
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const glm::dvec3 d = cam.ray_direction(x + 0.5, y + 0.5, w, h);
        glm::dvec3 p;
        bool on_box;
        std::uint8_t* c = f.color.px(x, y);
        if (hit(cam.position, d, p, on_box)) {
          f.depth[std::size_t(y) * w + x] = float(glm::dot(p - cam.position, fwd));
          if (on_box) {
            c[0] = 230, c[1] = 40, c[2] = 40, c[3] = 255;
          } else {
            ground_color(p, c);
          }
        } else {
          c[0] = kSkyColor[0], c[1] = kSkyColor[1], c[2] = kSkyColor[2], c[3] = 255;
        }
      }
    return f;
  }
};

Camera camera(glm::dvec3 pos, double yaw, double pitch, double roll, int w, int h) {
  Camera c;
  c.position = pos;
  c.yaw_deg = yaw;
  c.pitch_deg = pitch;
  c.roll_deg = roll;
  c.fov_y_deg = 50;
  c.aspect = double(w) / h;
  return c;
}

constexpr int W = 192, H = 128, M = 24;  // output size, margin on each side

double psnr(const Image& a, const Image& b) {
  return quality::psnr(a.view(), b.view()).rgb;
}

TEST(Warp, StaticCameraReturnsTheRealFrame) {
  const Scene scene{40, 300};
  const Camera c = camera({0, -900, 250}, 0, -15, 5, W, H);
  const Frame real = scene.render(with_margin(c, W, H, M, M), W + 2 * M, H + 2 * M);
  const Frame truth = scene.render(c, W, H);
  for (WarpMethod m : {WarpMethod::kDepth, WarpMethod::kPoly2}) {
    WarpOptions o;
    o.method = m;
    const WarpedFrame wf = warp_frame(real, c, W, H, o);
    EXPECT_EQ(wf.frame.cls, FrameClass::kWarp);
    EXPECT_EQ(wf.hole_fraction, 0.0) << to_string(m);
    // The central W x H pixels of the real frame, bit for bit.
    int differ = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        differ += std::memcmp(wf.frame.color.px(x, y), real.color.px(x + M, y + M), 4) != 0;
    EXPECT_EQ(differ, 0) << to_string(m);
    EXPECT_GT(psnr(wf.frame.color, truth.color), 60.0)
        << "the margin camera registers with the plain one";
  }
}

TEST(Warp, PureRotationIsExactUnderDepthAndNearlySoUnderPoly2) {
  // Looking down enough that no horizon is in view: a sharp edge would differ
  // by resampling alone, whatever the mapping.
  Scene scene;
  scene.period = 4.0;
  const glm::dvec3 eye(0, -800, 300);
  const Camera c0 = camera(eye, 0, -45, 0, W, H);
  const Frame real = scene.render(with_margin(c0, W, H, M, M), W + 2 * M, H + 2 * M);
  for (auto [dyaw, dpitch, droll] :
       {std::tuple{3.0, 0.0, 0.0}, std::tuple{0.0, 2.5, 0.0}, std::tuple{2.0, -1.5, 4.0}}) {
    const Camera c1 = camera(eye, dyaw, -45 + dpitch, droll, W, H);
    const Frame truth = scene.render(c1, W, H);
    WarpOptions o;
    const WarpedFrame d = warp_frame(real, c1, W, H, o);
    EXPECT_EQ(d.hole_fraction, 0.0) << "yaw " << dyaw << " pitch " << dpitch << " roll " << droll;
    EXPECT_GT(psnr(d.frame.color, truth.color), 40.0)
        << "yaw " << dyaw << " pitch " << dpitch << " roll " << droll;
    o.method = WarpMethod::kPoly2;
    const WarpedFrame p = warp_frame(real, c1, W, H, o);
    EXPECT_GT(psnr(p.frame.color, truth.color), 25.0)
        << "yaw " << dyaw << " pitch " << dpitch << " roll " << droll;
  }
}

TEST(Warp, Poly2RollIsARotationOfTheImage) {
  const Scene scene;
  const glm::dvec3 eye(0, -800, 300);
  const Camera c0 = camera(eye, 10, -20, 0, W, H), c1 = camera(eye, 10, -20, 6, W, H);
  const Frame real = scene.render(with_margin(c0, W, H, M, M), W + 2 * M, H + 2 * M);
  WarpOptions o;
  o.keep_sources = true;
  const WarpedFrame exact = warp_frame(real, c1, W, H, o);  // depth: exact under rotation
  o.method = WarpMethod::kPoly2;
  const WarpedFrame p = warp_frame(real, c1, W, H, o);
  // A rigid turn about the image centre by the roll angle, as the exact warp says.
  const double cx = W * 0.5 + M, cy = H * 0.5 + M;
  double worst = 0, worst_radius = 0, worst_exact = 0;
  for (int y = 0; y < H; y += 7)
    for (int x = 0; x < W; x += 7) {
      const std::size_t i = std::size_t(y) * W + x;
      const double r0 = std::hypot(x + 0.5 - W * 0.5, y + 0.5 - H * 0.5);
      const double r1 = std::hypot(p.source_x[i] - cx, p.source_y[i] - cy);
      worst_radius = std::max(worst_radius, std::abs(r1 - r0));
      const double a = std::atan2(p.source_y[i] - cy, p.source_x[i] - cx) -
                       std::atan2(y + 0.5 - H * 0.5, x + 0.5 - W * 0.5);
      if (r0 > 20) worst = std::max(worst, std::abs(std::remainder(a, 2 * kPi)) - 6 * kPi / 180);
      worst_exact = std::max({worst_exact, double(std::abs(p.source_x[i] - exact.source_x[i])),
                              double(std::abs(p.source_y[i] - exact.source_y[i]))});
    }
  EXPECT_LT(worst_radius, 0.01) << "pixels";
  EXPECT_LT(std::abs(worst), 1e-4) << "radians";
  EXPECT_LT(worst_exact, 0.1) << "pixels";
}

TEST(Warp, FlatPlaneTranslationFollowsTheAnalyticMapping) {
  const Scene scene;
  const Camera c0 = camera({0, -700, 200}, 5, -25, 0, W, H);
  Camera c1 = c0;
  c1.position += 12.0 * c0.right();  // sideways
  const int RW = W + 2 * M, RH = H + 2 * M;
  const Camera cr = with_margin(c0, W, H, M, M);
  const Frame real = scene.render(cr, RW, RH);
  WarpOptions o;
  o.keep_sources = true;
  const WarpedFrame d = warp_frame(real, c1, W, H, o);
  // Each pixel of the new view sees ground point P; the real frame saw P at
  // the projection of P through the margin camera.
  double worst = 0;
  int checked = 0;
  const glm::dvec3 f = cr.forward(), r = cr.right(), u = cr.up();
  const double t = std::tan(cr.fov_y_deg * kPi / 360);
  const double fy = RH / (2 * t), fx = RW / (2 * t * cr.aspect);
  for (int y = 0; y < H; y += 3)
    for (int x = 0; x < W; x += 3) {
      const glm::dvec3 dir = c1.ray_direction(x + 0.5, y + 0.5, W, H);
      if (dir.z > -0.05) continue;  // near the horizon one pixel spans kilometres
      const glm::dvec3 p = c1.position + (-c1.position.z / dir.z) * dir, q = p - cr.position;
      const double z = glm::dot(q, f);
      const double sx = RW * 0.5 + fx * glm::dot(q, r) / z, sy = RH * 0.5 - fy * glm::dot(q, u) / z;
      const std::size_t i = std::size_t(y) * W + x;
      ASSERT_FALSE(std::isnan(d.source_x[i])) << x << "," << y;
      worst = std::max({worst, std::abs(d.source_x[i] - sx), std::abs(d.source_y[i] - sy)});
      ++checked;
    }
  EXPECT_GT(checked, 500);
  EXPECT_LT(worst, 0.1) << "pixels";
  EXPECT_LT(d.hole_fraction, 0.001);
}

// New-view pixel (x, y) sees a surface point (or sky, a point at infinity)
// that the old camera c0 did not see.
bool hidden_from(const Scene& scene, const Camera& c0, const Camera& c1, int x, int y) {
  glm::dvec3 p, p0;
  bool box, box0;
  const glm::dvec3 dir = c1.ray_direction(x + 0.5, y + 0.5, W, H);
  if (!scene.hit(c1.position, dir, p, box)) return scene.hit(c0.position, dir, p0, box0);
  const glm::dvec3 back = p - c0.position;
  return scene.hit(c0.position, glm::normalize(back), p0, box0) &&
         glm::length(p0 - c0.position) < glm::length(back) - 1.0;
}

TEST(Warp, HoleMaskMarksTheDisocclusionBehindASpike) {
  const Scene scene{25, 400};  // a 50 m wide, 400 m tall box at the origin
  const Camera c0 = camera({0, -700, 150}, 0, -10, 0, W, H);
  Camera c1 = c0;
  c1.position.x += 40;  // step right: ground left-behind the box appears
  const Frame real = scene.render(with_margin(c0, W, H, M, M), W + 2 * M, H + 2 * M);
  const Frame truth = scene.render(c1, W, H);
  const WarpedFrame d = warp_frame(real, c1, W, H);
  // Pixels whose surface point (ground, the box's side, or sky) the old view
  // had behind the box: the true disocclusion.
  int truly = 0, marked_truly = 0, marked = 0, marked_far = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const bool hidden = hidden_from(scene, c0, c1, x, y);
      const bool m = d.holes[std::size_t(y) * W + x];
      truly += hidden;
      marked += m;
      marked_truly += m && hidden;
      // A marked pixel far (> 3 px) from any truly hidden one is a false alarm.
      if (m && !hidden) {
        bool near = false;
        for (int b = std::max(0, y - 3); b <= std::min(H - 1, y + 3) && !near; ++b)
          for (int a = std::max(0, x - 3); a <= std::min(W - 1, x + 3) && !near; ++a)
            near = hidden_from(scene, c0, c1, a, b);
        marked_far += !near;
      }
    }
  ASSERT_GT(truly, 100) << "the step should uncover ground behind the box";
  EXPECT_GT(marked_truly, 0.8 * truly);
  EXPECT_EQ(marked_far, 0);
  EXPECT_NEAR(d.hole_fraction, double(marked) / (W * H), 1e-12);
  // Outside the holes the warp matches the true view.
  EXPECT_GT(psnr(d.frame.color, truth.color), 20.0);

  // A second reference that saw the region (rendered from the new side)
  // fills the holes with the true ground.
  Camera c2 = c0;
  c2.position.x += 80;
  const Frame second = scene.render(with_margin(c2, W, H, M, M), W + 2 * M, H + 2 * M);
  const WarpedFrame filled = warp_frame(real, c1, W, H, {}, &second);
  EXPECT_EQ(filled.holes, d.holes) << "the mask is the primary's";
  EXPECT_GT(psnr(filled.frame.color, truth.color), psnr(d.frame.color, truth.color) + 3.0);
}

// Where the box moves over ground the old view saw, both land on the same
// new pixels: the splat's depth test keeps the box (the nearer) everywhere.
TEST(Warp, DepthWarpKeepsTheNearerSurfaceWhereTwoLand) {
  const Scene scene{25, 400};
  const Camera c0 = camera({0, -700, 150}, 0, -10, 0, W, H);
  Camera c1 = c0;
  c1.position.x -= 80;  // step left: the box slides right over the ground beside it
  const Frame real = scene.render(with_margin(c0, W, H, M, M), W + 2 * M, H + 2 * M);
  const Frame truth = scene.render(c1, W, H);
  const WarpedFrame d = warp_frame(real, c1, W, H);
  auto is_box = [](const std::uint8_t* c) { return c[0] == 230 && c[1] == 40 && c[2] == 40; };
  Scene ground = scene;
  ground.box_half = 0;
  int inside = 0, contested = 0, kept = 0;
  for (int y = 2; y + 2 < H; ++y)
    for (int x = 2; x + 2 < W; ++x) {
      // The box's interior in the true view (2 px from its edges, where a
      // crack takes the farther neighbour), where the old view saw it too
      // (not a newly seen face).
      bool all = !hidden_from(scene, c0, c1, x, y);
      for (int b = y - 2; b <= y + 2; ++b)
        for (int a = x - 2; a <= x + 2; ++a) all = all && is_box(truth.color.px(a, b));
      if (!all) continue;
      ++inside;
      // The ground behind the box on this pixel's ray, if the old view saw
      // it: then a ground pixel and a box pixel both land here.
      const glm::dvec3 ray = c1.ray_direction(x + 0.5, y + 0.5, W, H);
      glm::dvec3 g, p0;
      bool on_box;
      if (ground.hit(c1.position, ray, g, on_box)) {
        const glm::dvec3 back = g - c0.position;
        contested += !(scene.hit(c0.position, glm::normalize(back), p0, on_box) &&
                       glm::length(p0 - c0.position) < glm::length(back) - 1.0);
      }
      kept += is_box(d.frame.color.px(x, y));
    }
  ASSERT_GT(inside, 200);
  ASSERT_GT(contested, 100) << "the step should move the box over ground the old view saw";
  EXPECT_EQ(kept, inside);
}

TEST(Warp, WarpsAVoxelFrameCloseToItsRender) {
  TerrainOptions to;
  to.synthetic_size = 129;
  to.erosion_passes = 0;
  const Terrain t = load_terrain(to);
  const VoxelTerrain vt(t);
  const int w = 160, h = 90, m = 16;
  Camera c0 = camera({0, -0.5 * t.heights.extent(), t.heights.max_height() + 300}, 0, -20, 0, w, h);
  Camera c1 = c0;
  c1.position += 4.0 * c0.forward();
  c1.yaw_deg += 0.7;
  VoxelOptions o;
  o.threads = 2;
  VoxelRenderer big(vt, w + 2 * m, h + 2 * m, o), plain(vt, w, h, o);
  const Frame real = big.render(with_margin(c0, w, h, m, m));
  const Frame truth = plain.render(c1);
  for (WarpMethod meth : {WarpMethod::kDepth, WarpMethod::kPoly2}) {
    WarpOptions wo;
    wo.method = meth;
    const WarpedFrame wf = warp_frame(real, c1, w, h, wo);
    EXPECT_GT(psnr(wf.frame.color, truth.color), 24.0) << to_string(meth);
  }
}

// Bit for bit (NaN equals NaN).
bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

// A Warper writes every output pixel: reusing its buffers (which hold the
// previous call's pixels, holes and sources) gives what a fresh warp gives,
// across methods, sizes, second references and keep_sources.
TEST(Warp, WarperReuseMatchesAFreshWarp) {
  const Scene scene{25, 400};
  const Camera c0 = camera({0, -700, 150}, 0, -10, 0, W, H);
  Camera c1 = c0, c2 = c0;
  c1.position.x += 40;  // disoccludes ground behind the box: holes
  c2.position.x += 80;
  const Frame real = scene.render(with_margin(c0, W, H, M, M), W + 2 * M, H + 2 * M);
  const Frame second = scene.render(with_margin(c2, W, H, M, M), W + 2 * M, H + 2 * M);
  struct Call {
    WarpMethod method;
    int w, h;
    bool sources;
    const Frame* second;
  };
  const Call calls[] = {
      {WarpMethod::kDepth, W, H, true, nullptr},  {WarpMethod::kPoly2, W, H, false, nullptr},
      {WarpMethod::kDepth, W, H, false, &second}, {WarpMethod::kDepth, W / 2, H / 2, true, nullptr},
      {WarpMethod::kPoly2, W, H, true, nullptr},  {WarpMethod::kDepth, W, H, true, nullptr}};
  Warper warper;
  for (const Call& c : calls) {
    WarpOptions o;
    o.method = c.method;
    o.keep_sources = c.sources;
    const WarpedFrame fresh = warp_frame(real, c1, c.w, c.h, o, c.second);
    const WarpedFrame& reused = warper.warp(real, c1, c.w, c.h, o, c.second);
    const std::string what = fmt::format("{} {}x{}", to_string(c.method), c.w, c.h);
    EXPECT_EQ(reused.frame.color.rgba, fresh.frame.color.rgba) << what;
    EXPECT_EQ(reused.frame.color.width, c.w) << what;
    EXPECT_TRUE(same_bits(reused.frame.depth, fresh.frame.depth)) << what;
    EXPECT_EQ(reused.holes, fresh.holes) << what;
    EXPECT_EQ(reused.hole_fraction, fresh.hole_fraction) << what;
    EXPECT_EQ(reused.frame.cls, FrameClass::kWarp);
    EXPECT_TRUE(same_bits(reused.source_x, fresh.source_x)) << what;
    EXPECT_TRUE(same_bits(reused.source_y, fresh.source_y)) << what;
  }
  EXPECT_GT(warp_frame(real, c1, W, H).hole_fraction, 0.001) << "the scene should have holes";
}

TEST(Warp, RejectsFramesWithoutDepthAndBadSizes) {
  Frame f;
  f.color = Image(4, 4);
  EXPECT_THROW(warp_frame(f, Camera{}, 4, 4), InputError);
  f.depth.assign(16, 10.f);
  EXPECT_THROW(warp_frame(f, Camera{}, 0, 4), InputError);
  EXPECT_THROW(parse_warp_method("affine"), InputError);
  EXPECT_NO_THROW(warp_frame(f, Camera{}, 4, 4));
  // A reference one pixel wide (the span kernels read 2 x 2 blocks).
  Frame thin;
  thin.color = Image(1, 4);
  thin.depth.assign(4, 10.f);
  for (WarpMethod m : {WarpMethod::kDepth, WarpMethod::kPoly2}) {
    WarpOptions o;
    o.method = m;
    EXPECT_EQ(warp_frame(thin, Camera{}, 3, 5, o).frame.color.width, 3) << to_string(m);
  }
}

TEST(Warp, BilinearSpanMatchesBilinearBlock) {
  // Random texels, positions anywhere (clamped, NaN, exact centres) and a
  // span length that leaves a tail after the vector loop's groups of four.
  const int w = 37, h = 11, n = 203;
  std::mt19937 rng(7);
  std::vector<std::uint32_t> src(std::size_t(w) * h);
  for (auto& t : src) t = std::uint32_t(rng());
  std::uniform_real_distribution<float> pos(-3.f, 40.f);
  std::vector<int> off(n);
  std::vector<std::uint32_t> wx(n), wy(n), span(n);
  for (int k = 0; k < n; ++k) {
    float x = pos(rng), y = pos(rng) * 0.3f;
    if (k % 17 == 0) x = float(k % w) + 0.5f;
    if (k == 5) x = std::numeric_limits<float>::quiet_NaN();
    warp::tap(x, y, w, h, off[k], wx[k], wy[k]);
  }
  warp::bilinear_span(src.data(), w, off.data(), wx.data(), wy.data(), n, span.data());
  for (int k = 0; k < n; ++k)
    ASSERT_EQ(span[k], warp::bilinear_block(src.data(), off[k], w, wx[k], wy[k])) << k;
}

}  // namespace
}  // namespace terrasprite
