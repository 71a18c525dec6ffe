// SPDX-License-Identifier: MIT
#include "terrasprite/camera/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

Camera Camera::look_at(glm::dvec3 eye, glm::dvec3 target, double fov_y_deg, double aspect,
                       double yaw_hint_deg) {
  Camera c;
  c.position = eye;
  c.fov_y_deg = fov_y_deg;
  c.aspect = aspect;
  glm::dvec3 d = target - eye;
  double len = glm::length(d);
  d = len > 0 ? d / len : glm::dvec3(0, 1, 0);
  c.pitch_deg = std::asin(std::clamp(d.z, -1.0, 1.0)) / kRadiansPerDegree;
  double horizontal = std::hypot(d.x, d.y);
  c.yaw_deg = horizontal > 1e-9 ? std::atan2(d.x, d.y) / kRadiansPerDegree : yaw_hint_deg;
  return c;
}

glm::dvec3 Camera::forward() const {
  double y = yaw_deg * kRadiansPerDegree, p = pitch_deg * kRadiansPerDegree;
  return {std::cos(p) * std::sin(y), std::cos(p) * std::cos(y), std::sin(p)};
}

// Right and up before roll: right is horizontal, up completes the frame.
static void unrolled_basis(const Camera& c, glm::dvec3& r0, glm::dvec3& u0) {
  double y = c.yaw_deg * kRadiansPerDegree;
  r0 = {std::cos(y), -std::sin(y), 0.0};
  u0 = glm::cross(r0, c.forward());
}

glm::dvec3 Camera::right() const {
  glm::dvec3 r0, u0;
  unrolled_basis(*this, r0, u0);
  double a = roll_deg * kRadiansPerDegree;
  return std::cos(a) * r0 - std::sin(a) * u0;
}

glm::dvec3 Camera::up() const {
  glm::dvec3 r0, u0;
  unrolled_basis(*this, r0, u0);
  double a = roll_deg * kRadiansPerDegree;
  return std::cos(a) * u0 + std::sin(a) * r0;
}

glm::dmat4 Camera::view() const {
  glm::dvec3 r = right(), u = up(), f = forward();
  glm::dmat4 m(1.0);
  m[0][0] = r.x;
  m[1][0] = r.y;
  m[2][0] = r.z;
  m[0][1] = u.x;
  m[1][1] = u.y;
  m[2][1] = u.z;
  m[0][2] = -f.x;
  m[1][2] = -f.y;
  m[2][2] = -f.z;
  m[3][0] = -glm::dot(r, position);
  m[3][1] = -glm::dot(u, position);
  m[3][2] = glm::dot(f, position);
  return m;
}

glm::dmat4 Camera::projection() const {
  return glm::perspectiveRH_NO(fov_y_deg * kRadiansPerDegree, aspect, near_m, far_m);
}

double Camera::pixel_angle(int height_px) const {
  return fov_y_deg * kRadiansPerDegree / height_px;
}

glm::dvec3 Camera::ray_direction(double px, double py, int width, int height) const {
  double t = std::tan(fov_y_deg * kRadiansPerDegree * 0.5);
  double x = (2.0 * px / width - 1.0) * t * aspect;
  double y = (1.0 - 2.0 * py / height) * t;
  return glm::normalize(forward() + x * right() + y * up());
}

void fit_clip_planes(Camera& c, const Heightfield& h) {
  const double hx = h.extent_x() * 0.5, hy = h.extent_y() * 0.5;
  const double z0 = h.min_height(), z1 = h.max_height();
  double far_d = 0;
  for (int k = 0; k < 8; ++k) {
    glm::dvec3 corner((k & 1) ? hx : -hx, (k & 2) ? hy : -hy, (k & 4) ? z1 : z0);
    far_d = std::max(far_d, glm::length(corner - c.position));
  }
  // Distance to the terrain's bounding box (0 inside it) and height above the
  // ground below bound how near visible terrain can be.
  glm::dvec3 p = c.position;
  glm::dvec3 q(std::clamp(p.x, -hx, hx), std::clamp(p.y, -hy, hy), std::clamp(p.z, z0, z1));
  double box = glm::length(p - q);
  double above = p.z - h.sample(p.x, p.y);
  double near_d = std::max(box, 0.25 * std::abs(above));
  c.far_m = std::max(far_d * 1.05, 1.0);
  c.near_m = std::clamp(near_d * 0.5, std::max(0.05, c.far_m * 1e-5), c.far_m * 0.5);
}

}  // namespace terrasprite
