// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/instance_view.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "hybrid/sphere_tangents.h"

namespace terrasprite {
namespace {

/// Radical inverse of i in base b (a Halton sequence's coordinate).
double radical_inverse(int i, int b) {
  double f = 1, x = 0;
  for (; i > 0; i /= b) {
    f /= b;
    x += f * (i % b);
  }
  return x;
}

/// 512 points spread evenly through the unit ball: Halton (2, 3, 5) over its
/// cube, those inside kept. A plane cuts them within a percent or two of the
/// ball's volume; a regular 8 x 8 x 8 grid missed a cap by 4 points in 100.
const std::vector<glm::dvec3>& ball_points() {
  static const std::vector<glm::dvec3> points = [] {
    std::vector<glm::dvec3> p;
    for (int i = 1; p.size() < 512; ++i) {
      const glm::dvec3 q{radical_inverse(i, 2) * 2 - 1, radical_inverse(i, 3) * 2 - 1,
                         radical_inverse(i, 5) * 2 - 1};
      if (glm::dot(q, q) <= 1) p.push_back(q);
    }
    return p;
  }();
  return points;
}

/// The part of the ball at (x, y, z) (camera frame: right, up, forward;
/// metres) of radius r inside the frustum x/z in [-tx, tx], y/z in [-ty, ty],
/// z >= near: the share of ball_points() in it. For a ball the frustum's
/// planes cut (view_instance returns 1 for one wholly inside).
double ball_fraction_in_frustum(double x, double y, double z, double r, double tx, double ty,
                                double near_m) {
  int in = 0;
  for (const glm::dvec3& q : ball_points()) {
    const double px = x + r * q.x, py = y + r * q.y, pz = z + r * q.z;
    in += pz >= near_m && std::abs(px) <= tx * pz && std::abs(py) <= ty * pz;
  }
  return double(in) / double(ball_points().size());
}

}  // namespace

InstanceView view_instance(const Camera& camera, int height_px, const ObjectInstance& instance,
                           glm::dvec3 center_m, double radius_m) {
  const double heading = glm::radians(instance.heading_deg);
  const glm::dvec3 centre = instance.position + heading_rotate(center_m * instance.scale, heading);
  const double r = radius_m * instance.scale;
  InstanceView v;
  v.centre_m = centre;
  v.radius_m = r;
  const glm::dvec3 to = centre - camera.position;
  v.distance_m = glm::length(to);
  // Frustum test on the sphere: depth along the view axis, then the four
  // side planes through the eye.
  const glm::dvec3 f = camera.forward(), rt = camera.right(), up = camera.up();
  const double z = glm::dot(to, f);
  const double ty = std::tan(glm::radians(camera.fov_y_deg) / 2), tx = ty * camera.aspect;
  const double x = glm::dot(to, rt), y = glm::dot(to, up);
  const double ny = 1.0 / std::sqrt(1 + ty * ty), nx = 1.0 / std::sqrt(1 + tx * tx);
  // Signed distances from the centre to the nearer side planes (outwards).
  const double side_x = (std::abs(x) - tx * z) * nx, side_y = (std::abs(y) - ty * z) * ny;
  v.visible = z + r > camera.near_m && z - r < camera.far_m && side_x < r && side_y < r;
  if (!v.visible) return v;
  v.size_px = v.distance_m > r
                  ? height_px * (r / std::sqrt(v.distance_m * v.distance_m - r * r)) / ty
                  : double(height_px);
  v.size_px = std::min(v.size_px, 4.0 * height_px);
  // The pixels it can cover: the sphere's silhouette's extent along each
  // image axis, clipped to the image, and the ellipse inscribed in that
  // box. Each extent is exact: the tangent planes through the eye that
  // contain the other axis. (A disc of size_px around the projected centre
  // is right for far spheres only: a near one's centre can project far
  // outside the image while the sphere fills a side of it. Such an
  // instance got no pixels, so no weight, and the policy drew it at its
  // coarsest: a forest patch the camera stood in became a green slab, and
  // the frame's object SSIM fell to 0.79.)
  const double width_px = height_px * camera.aspect;
  auto extent = [&](double across, double tan_half, double extent_px) {
    const double to_px = extent_px / 2 / tan_half;
    double lo = 0, hi = 0;  // slopes of the two tangents, times to_px
    if (z > r) {            // both tangents in front of the eye (nearly every instance)
      const auto [a, b] = tangent_slopes(across, z, r);
      lo = a * to_px;
      hi = b * to_px;
    } else {  // one tangent lies behind the eye: by angle, past +-90 degrees unbounded
      const double d = std::hypot(across, z);
      if (d <= r) return extent_px;  // the eye is within the sphere's slab: it spans the axis
      const double centre = std::atan2(across, z), half = std::asin(r / d);
      auto at = [&](double a) {
        return a <= -M_PI / 2 ? -INFINITY : a >= M_PI / 2 ? INFINITY : std::tan(a) * to_px;
      };
      lo = at(centre - half);
      hi = at(centre + half);
    }
    return std::max(0.0, std::min(hi, extent_px / 2) - std::max(lo, -extent_px / 2));
  };
  v.pixels = M_PI / 4 * extent(x, tx, width_px) * extent(y, ty, double(height_px));
  const bool inside = z - r >= camera.near_m && side_x <= -r && side_y <= -r;
  v.on_screen = inside ? 1.0 : ball_fraction_in_frustum(x, y, z, r, tx, ty, camera.near_m);
  // The camera's direction from the centre, in the model's frame.
  const glm::dvec3 d = heading_rotate(-to / std::max(v.distance_m, 1e-12), -heading);
  v.theta_deg = glm::degrees(std::acos(std::clamp(d.z, -1.0, 1.0)));
  v.phi_deg = glm::degrees(std::atan2(-d.x, -d.y));
  if (v.phi_deg < 0) v.phi_deg += 360.0;
  v.heading_deg = instance.heading_deg;
  return v;
}

}  // namespace terrasprite
