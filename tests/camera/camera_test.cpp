// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "terrasprite/camera/camera.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/synth.h"
#include "test_util.h"

using namespace terrasprite;

namespace {
Heightfield flat(int n, double spacing, float z = 0) {
  Heightfield h;
  h.width = h.height = n;
  h.spacing_x = h.spacing_y = spacing;
  h.heights.assign(std::size_t(n) * n, z);
  return h;
}
void expect_vec(glm::dvec3 a, glm::dvec3 b, double tol = 1e-9) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}
}  // namespace

TEST(Camera, YawPitchRollBasis) {
  Camera c;
  expect_vec(c.forward(), {0, 1, 0});
  expect_vec(c.right(), {1, 0, 0});
  expect_vec(c.up(), {0, 0, 1});
  c.yaw_deg = 90;
  expect_vec(c.forward(), {1, 0, 0});
  c.yaw_deg = 0;
  c.pitch_deg = -90;
  expect_vec(c.forward(), {0, 0, -1});
  expect_vec(c.up(), {0, 1, 0});  // looking down, image top points north
  c.pitch_deg = 0;
  c.roll_deg = 90;
  expect_vec(c.up(), {1, 0, 0});
}

TEST(Camera, LookAtAndProjectionAgreeWithRays) {
  Camera c = Camera::look_at({100, -200, 300}, {0, 0, 0}, 50, 1.5);
  c.near_m = 1;
  c.far_m = 1000;
  expect_vec(c.forward(), glm::normalize(glm::dvec3(-100, 200, -300)));
  // A point along a pixel's ray projects back onto that pixel.
  const int w = 300, h = 200;
  glm::dvec3 d = c.ray_direction(30.5, 170.5, w, h);
  glm::dvec4 clip = c.view_projection() * glm::dvec4(c.position + 50.0 * d, 1.0);
  double px = (clip.x / clip.w * 0.5 + 0.5) * w, py = (0.5 - clip.y / clip.w * 0.5) * h;
  EXPECT_NEAR(px, 30.5, 1e-6);
  EXPECT_NEAR(py, 170.5, 1e-6);
  EXPECT_NEAR(c.pixel_angle(h), glm::radians(50.0) / h, 1e-15);
}

TEST(PaperPath, FramesShapeAndClearance) {
  SynthOptions s;
  s.size = 129;
  Heightfield h = synthesize_terrain(s);
  auto path = paper_path(h, 460, 1.0);
  ASSERT_EQ(path.size(), 460u);
  const double E = h.extent();
  EXPECT_NEAR(path[0].pitch_deg, -90, 1e-9);
  EXPECT_NEAR(glm::length(path[0].position - glm::dvec3(0, 0, h.sample(0, 0))), 1.3 * E, 1e-6);
  EXPECT_NEAR(path[59].pitch_deg, -(20 + 70.0 / 60), 0.01);
  EXPECT_NEAR(path[60].pitch_deg, -20, 1e-6);
  EXPECT_NEAR(path[459].fov_y_deg, 60, 1e-12);
  for (const Camera& c : path)
    EXPECT_GE(c.position.z - h.sample(c.position.x, c.position.y), 0.03 * E - 1e-6);
  // Continuous: no jump between consecutive frames beyond a small part of E.
  for (std::size_t i = 1; i < path.size(); ++i) {
    EXPECT_LT(glm::length(path[i].position - path[i - 1].position), 0.05 * E) << i;
    EXPECT_LT(
        glm::degrees(std::acos(std::min(1.0, glm::dot(path[i].forward(), path[i - 1].forward())))),
        3.0)
        << i;
  }
  // Deterministic and any frame count samples the same flight.
  auto again = paper_path(h, 460, 1.0);
  EXPECT_EQ(again[200].position, path[200].position);
  auto short_path = paper_path(h, 115, 1.0);
  ASSERT_EQ(short_path.size(), 115u);
  expect_vec(short_path.back().position, path.back().position, 1e-6);
  EXPECT_THROW(paper_path(h, 0, 1.0), InputError);
}

TEST(PaperPath, ClipPlanesEncloseTheTerrain) {
  Heightfield h = flat(33, 10, 50);
  for (const Camera& c : paper_path(h, 20, 1.0)) {
    EXPECT_GT(c.near_m, 0);
    for (int k = 0; k < 4; ++k) {  // every terrain corner lies inside the far plane
      glm::dvec3 corner((k & 1) ? 160.0 : -160.0, (k & 2) ? 160.0 : -160.0, 50.0);
      EXPECT_GT(c.far_m, glm::length(corner - c.position));
    }
    EXPECT_LT(c.near_m, glm::length(c.position - glm::dvec3(0, 0, 50)));
  }
}

TEST(JsonPath, InterpolatesThroughKeyframes) {
  tstest::TempDir tmp;
  std::ofstream(tmp / "p.json") << R"({"keyframes": [
    {"t": 0, "position": [0, -100, 50], "target": [0, 0, 0]},
    {"t": 1, "position": [100, 0, 50], "yaw_deg": -90, "pitch_deg": -10},
    {"t": 3, "position": [0, 100, 80], "yaw_deg": 180, "pitch_deg": -20, "roll_deg": 5, "fov_deg": 40}]})";
  Heightfield h = flat(11, 10);
  auto p = load_path_file(tmp / "p.json", h, 31, 1.0);
  ASSERT_EQ(p.size(), 31u);
  expect_vec(p[0].position, {0, -100, 50}, 1e-9);
  expect_vec(p[10].position, {100, 0, 50}, 1e-9);  // t = 1 lands on the keyframe
  EXPECT_NEAR(p[10].yaw_deg, -90, 1e-6);
  EXPECT_NEAR(p[10].pitch_deg, -10, 1e-6);
  EXPECT_NEAR(p[30].roll_deg, 5, 1e-6);
  EXPECT_NEAR(p[30].fov_y_deg, 40, 1e-9);
  for (std::size_t i = 1; i < p.size(); ++i)
    EXPECT_LT(glm::length(p[i].position - p[i - 1].position), 30.0);
}

TEST(JsonPath, MalformedFilesNameTheProblem) {
  tstest::TempDir tmp;
  Heightfield h = flat(11, 10);
  auto expect_error = [&](const std::string& text, const std::string& fragment) {
    std::ofstream(tmp / "bad.json") << text;
    try {
      load_path_file(tmp / "bad.json", h, 5, 1.0);
      ADD_FAILURE() << "no error for " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error("{not json", "malformed JSON");
  expect_error(R"({"keyframes": []})", "keyframes");
  expect_error(R"({"keyframes": [{"t": 0}]})", "position");
  expect_error(R"({"keyframes": [{"t": 0, "position": [1, 2]}]})", "position");
  expect_error(R"({"keyframes": [{"t": 0, "position": [1, 2, 3]}]})", "target");
  expect_error(
      R"({"keyframes": [{"t": 1, "position": [1,2,3], "yaw_deg": 0}, {"t": 1, "position": [1,2,3], "yaw_deg": 0}]})",
      "greater");
  EXPECT_THROW(load_path_file(tmp / "missing.json", h, 5, 1.0), InputError);
}

TEST(JsonPath, ExampleFileLoads) {
  Heightfield h = flat(11, 10);
  auto p = load_path_file(std::string(TS_SOURCE_DIR) + "/examples/path.json", h, 50, 1.0);
  EXPECT_EQ(p.size(), 50u);
}
