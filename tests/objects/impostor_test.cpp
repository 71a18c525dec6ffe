// SPDX-License-Identifier: MIT
// Impostors against the mesh they were built from: a box of known colours.
#include <gtest/gtest.h>

#include <cstdlib>

#include "gl/render_target.h"
#include "object_test_util.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/object_renderer.h"
#include "terrasprite/quality/quality.h"

namespace ts = terrasprite;

namespace {

constexpr int kSize = 128;

struct Shot {
  ts::Image color;
  std::vector<float> depth;
};

// Renders `draw` into a fresh target; TS_OBJECT_PNG=dir saves the image.
template <typename Draw>
Shot shoot(ts::gl::RenderTarget& target, const ts::Camera& cam, Draw draw, const char* name) {
  target.bind_and_clear();
  draw();
  glFinish();
  Shot s{target.read_color(), target.read_depth(cam.near_m, cam.far_m)};
  if (const char* dir = std::getenv("TS_OBJECT_PNG"))
    ts::save_png(s.color, std::string(dir) + "/" + name + ".png");
  return s;
}

std::vector<std::uint8_t> coverage(const Shot& a, const Shot& b) {
  std::vector<std::uint8_t> m(a.depth.size());
  for (std::size_t i = 0; i < m.size(); ++i)
    m[i] = std::isfinite(a.depth[i]) || std::isfinite(b.depth[i]);
  return m;
}

class Impostor : public ::testing::Test {
 protected:
  ts::GlContext ctx;
  ts::gl::RenderTarget target{kSize, kSize};
  ts::Model box = tstest::colored_box();
  ts::GlModel gl_box{box, ts::build_lod_chain(box)};
  ts::ObjectInstance at_origin;
};

}  // namespace

TEST_F(Impostor, ReliefMatchesMeshThroughAFace) {
  const ts::Camera cam = tstest::orbit({0, 0, 0.5}, 4.0, 0, 0);  // looking north at the -y face
  const ts::Representation mesh{ts::ObjectKind::kMesh}, relief{ts::ObjectKind::kRelief, 0, 64};
  gl_box.prepare(relief);
  const Shot a = shoot(
      target, cam, [&] { gl_box.draw(mesh, std::span(&at_origin, 1), cam); }, "face_mesh");
  const Shot b = shoot(
      target, cam, [&] { gl_box.draw(relief, std::span(&at_origin, 1), cam); }, "face_relief");
  const auto mask = coverage(a, b);
  EXPECT_GT(ts::quality::ssim(a.color.view(), b.color.view(), {}, mask).ssim, 0.99);
  // Depth within one texel's depth step of the box (1.01 m / 64).
  const double step = 1.01 / 64;
  int both = 0;
  for (std::size_t i = 0; i < a.depth.size(); ++i)
    if (std::isfinite(a.depth[i]) && std::isfinite(b.depth[i])) {
      ++both;
      EXPECT_NEAR(a.depth[i], b.depth[i], step) << "pixel " << i;
    }
  EXPECT_GT(both, kSize * kSize / 20);
}

TEST_F(Impostor, ReliefBetweenTwoFaces) {
  const ts::Camera cam = tstest::orbit({0, 0, 0.5}, 4.0, 45, 20);
  const ts::Representation mesh{ts::ObjectKind::kMesh}, relief{ts::ObjectKind::kRelief, 0, 64};
  gl_box.prepare(relief);
  const Shot a = shoot(
      target, cam, [&] { gl_box.draw(mesh, std::span(&at_origin, 1), cam); }, "diag_mesh");
  const Shot b = shoot(
      target, cam, [&] { gl_box.draw(relief, std::span(&at_origin, 1), cam); }, "diag_relief");
  const auto mask = coverage(a, b);
  const double s = ts::quality::ssim(a.color.view(), b.color.view(), {}, mask).ssim;
  RecordProperty("ssim_45deg", std::to_string(s));
  EXPECT_GT(s, 0.90);  // measured 0.93: silhouette and edge texels (nearest sampling)
}

TEST_F(Impostor, OctahedralMatchesMesh) {
  const ts::Camera cam = tstest::orbit({0, 0, 0.5}, 4.0, 30, 25);
  const ts::Representation mesh{ts::ObjectKind::kMesh}, oct{ts::ObjectKind::kOctahedral, 0, 64, 12};
  gl_box.prepare(oct);
  const Shot a = shoot(
      target, cam, [&] { gl_box.draw(mesh, std::span(&at_origin, 1), cam); }, "oct_mesh");
  const Shot b = shoot(
      target, cam, [&] { gl_box.draw(oct, std::span(&at_origin, 1), cam); }, "oct_impostor");
  const auto mask = coverage(a, b);
  const double s = ts::quality::ssim(a.color.view(), b.color.view(), {}, mask).ssim;
  RecordProperty("ssim", std::to_string(s));
  EXPECT_GT(
      s, 0.88);  // measured 0.92 (0.79 before the fixes of issue-10-s9): blended views soften edges
}

TEST_F(Impostor, HalfHiddenBehindAWall) {
  // A wall standing 1.5 m in front of the box hides its lower half: the
  // impostor must write true depth for the wall to win there.
  ts::Model wall = tstest::colored_box(3.f, 0.1f, 0.5f);
  ts::GlModel gl_wall{wall, {ts::build_lod_chain(wall).front()}};
  const ts::ObjectInstance wall_at{{0, -1.5, 0}, 0, 1};
  const ts::Camera cam = tstest::orbit({0, 0, 0.5}, 4.0, 0, 5);
  const ts::Representation mesh{ts::ObjectKind::kMesh}, relief{ts::ObjectKind::kRelief, 0, 64};
  gl_box.prepare(relief);
  auto scene = [&](const ts::Representation& rep) {
    return [&, rep] {
      gl_wall.draw(mesh, std::span(&wall_at, 1), cam);
      gl_box.draw(rep, std::span(&at_origin, 1), cam);
    };
  };
  const Shot a = shoot(target, cam, scene(mesh), "wall_mesh");
  const Shot b = shoot(target, cam, scene(relief), "wall_relief");
  EXPECT_GT(ts::quality::ssim(a.color.view(), b.color.view()).ssim, 0.99);
}

TEST_F(Impostor, GroupsDrawnAtOnceMatchGroupsDrawnOneByOne) {
  // Three boxes, each its own representation: one upload, three draws at
  // their offsets in the instance buffer, as three separate draws would.
  const ts::Camera cam = tstest::orbit({0, 0, 0.5}, 7.0, 20, 15);
  const ts::Representation mesh{ts::ObjectKind::kMesh}, relief{ts::ObjectKind::kRelief, 0, 64},
      oct{ts::ObjectKind::kOctahedral, 0, 64, 8};
  gl_box.prepare(relief);
  gl_box.prepare(oct);
  target.bind_and_clear();  // prepare binds its own framebuffer
  const ts::ObjectInstance left{{-1.6, 0, 0}, 30, 1}, mid{{0, 0, 0}, 0, 0.8},
      right{{1.6, 0, 0}, -20, 1.2};
  const std::vector<ts::GlModel::Group> groups = {
      {mesh, std::span(&left, 1)}, {relief, std::span(&mid, 1)}, {oct, std::span(&right, 1)}};
  const Shot one_by_one = shoot(
      target, cam,
      [&] {
        for (const auto& g : groups) gl_box.draw(g.rep, g.instances, cam);
      },
      "groups_one_by_one");
  const Shot at_once = shoot(
      target, cam, [&] { gl_box.draw(groups, cam); }, "groups_at_once");
  EXPECT_EQ(one_by_one.color.rgba, at_once.color.rgba);
  int covered = 0;
  for (float d : at_once.depth) covered += std::isfinite(d);
  EXPECT_GT(covered, kSize * kSize / 20);
}
