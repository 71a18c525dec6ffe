// SPDX-License-Identifier: MIT
// A camera as the warp uses it: pixel <-> world with linear depth, and the
// bilinear reads of a reference frame.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>

#include "common/packed_rgba.h"
#include "terrasprite/camera/camera.h"
#include "terrasprite/camera/frame.h"

namespace terrasprite::warp {

/// Image coordinates are pixels, x right, y down, pixel centres at +0.5;
/// depth is metres along the view axis (Frame's convention).
struct Pinhole {
  glm::dvec3 eye, r, u, f;
  double fx, fy, mx, my;
  int w, h;

  Pinhole(const Camera& c, int width, int height)
      : eye(c.position), r(c.right()), u(c.up()), f(c.forward()), w(width), h(height) {
    const double t = std::tan(c.fov_y_deg * 3.14159265358979323846 / 360.0);
    fx = width / (2.0 * t * c.aspect);
    fy = height / (2.0 * t);
    mx = width * 0.5;
    my = height * 0.5;
  }
  /// Ray through (x, y) with unit forward component.
  glm::dvec3 ray(double x, double y) const { return f + ((x - mx) / fx) * r - ((y - my) / fy) * u; }
  glm::dvec3 unproject(double x, double y, double depth) const { return eye + depth * ray(x, y); }
  /// World point -> image; false behind (or at) the eye.
  bool project(const glm::dvec3& p, double& x, double& y, double& depth) const {
    const glm::dvec3 q = p - eye;
    depth = glm::dot(q, f);
    if (!(depth > 1e-9)) return false;
    x = mx + fx * glm::dot(q, r) / depth;
    y = my - fy * glm::dot(q, u) / depth;
    return true;
  }
  /// Direction (a point at infinity) -> image; false behind the eye.
  bool project_dir(const glm::dvec3& d, double& x, double& y) const {
    const double z = glm::dot(d, f);
    if (!(z > 1e-12)) return false;
    x = mx + fx * glm::dot(d, r) / z;
    y = my - fy * glm::dot(d, u) / z;
    return true;
  }
};

/// A reference frame for reading: its camera model and bilinear reads.
struct Reference {
  const Frame& frame;
  Pinhole cam;
  explicit Reference(const Frame& f) : frame(f), cam(f.camera, f.width(), f.height()) {}

  bool inside(double x, double y) const { return x >= 0 && y >= 0 && x <= cam.w && y <= cam.h; }
  float depth_nearest(double x, double y) const {
    const int i = std::clamp(int(x), 0, cam.w - 1), j = std::clamp(int(y), 0, cam.h - 1);
    return frame.depth[std::size_t(j) * cam.w + i];
  }
  /// Depth at (x, y): bilinear over a surface, nearest across a silhouette or sky.
  float depth_at(double x, double y) const {
    const double sx = std::clamp(x - 0.5, 0.0, double(cam.w - 1));
    const double sy = std::clamp(y - 0.5, 0.0, double(cam.h - 1));
    const int i0 = std::min(int(sx), std::max(cam.w - 2, 0)),
              j0 = std::min(int(sy), std::max(cam.h - 2, 0));
    const int i1 = std::min(i0 + 1, cam.w - 1), j1 = std::min(j0 + 1, cam.h - 1);
    const float* d = frame.depth.data();
    const float a = d[std::size_t(j0) * cam.w + i0], b = d[std::size_t(j0) * cam.w + i1];
    const float c = d[std::size_t(j1) * cam.w + i0], e = d[std::size_t(j1) * cam.w + i1];
    const float lo = std::min({a, b, c, e}), hi = std::max({a, b, c, e});
    if (!(hi < Frame::kSky) || hi - lo > 0.05f * lo) return depth_nearest(x, y);
    const float fi = float(sx - i0), fj = float(sy - j0);
    const float top = a + (b - a) * fi, bot = c + (e - c) * fi;
    return top + (bot - top) * fj;
  }
  /// Bilinear RGBA at (x, y), clamped to the image.
  void color_at(double x, double y, std::uint8_t out[4]) const {
    bilinear_rgba(frame.color, x, y, out);
  }

  /// Bilinear RGBA of `img` at (x, y), clamped; 8-bit weights (exact at
  /// pixel centres).
  static void bilinear_rgba(const Image& img, double x, double y, std::uint8_t out[4]) {
    const std::uint32_t c = bilinear_packed(img, float(x), float(y));
    std::memcpy(out, &c, 4);
  }
  static std::uint32_t bilinear_packed(const Image& img, float x, float y) {
    const float sx = std::clamp(x - 0.5f, 0.f, float(img.width - 1));
    const float sy = std::clamp(y - 0.5f, 0.f, float(img.height - 1));
    const int i0 = std::min(int(sx), std::max(img.width - 2, 0));
    const int j0 = std::min(int(sy), std::max(img.height - 2, 0));
    const int di = i0 + 1 < img.width ? 1 : 0;
    const std::size_t row = j0 + 1 < img.height ? std::size_t(img.width) : 0;
    const std::uint32_t fi = std::uint32_t((sx - float(i0)) * 256.f + 0.5f);
    const std::uint32_t fj = std::uint32_t((sy - float(j0)) * 256.f + 0.5f);
    const std::uint8_t* p = img.rgba.data() + (std::size_t(j0) * img.width + i0) * 4;
    std::uint32_t a, b, c, d;
    std::memcpy(&a, p, 4);
    std::memcpy(&b, p + 4 * di, 4);
    std::memcpy(&c, p + 4 * row, 4);
    std::memcpy(&d, p + 4 * (row + di), 4);
    return lerp_packed(lerp_packed(a, b, fi), lerp_packed(c, d, fi), fj);
  }
};

}  // namespace terrasprite::warp
