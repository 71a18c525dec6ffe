// SPDX-License-Identifier: MIT
// How a camera sees one object instance: inside the view frustum or not,
// its on-screen size and the viewing angles in the model's own frame (the
// quality tables' phi and theta).
#pragma once
#include <glm/glm.hpp>

#include "terrasprite/camera/camera.h"
#include "terrasprite/objects/object_renderer.h"

namespace terrasprite {

struct InstanceView {
  bool visible = false;    ///< bounding sphere touches the view frustum
  double distance_m = 0;   ///< camera to sphere centre
  glm::dvec3 centre_m{0};  ///< bounding sphere's centre, world metres (heading and scale applied)
  double radius_m = 0;     ///< its radius, metres (scale applied)
  /// Diameter of the bounding sphere on screen, pixels (the tables' size_px);
  /// the full image height when the camera is inside the sphere.
  double size_px = 0;
  /// Pixels the instance can cover: the ellipse inscribed in its bounding
  /// sphere's on-screen box (exact per axis, near spheres included),
  /// clipped to the image; a far sphere's is its disc, pi/4 size_px^2.
  double pixels = 0;
  /// The part of the bounding ball inside the view frustum (its volume,
  /// sampled on 512 fixed points: 1/512 steps), [0, 1]: how much of a mesh
  /// reaches the rasteriser (DrawCostModel::instance_ms). For a model's
  /// triangles spread through its ball this is the part on screen, the
  /// camera within the ball included (a forest walked through).
  double on_screen = 1;
  double phi_deg = 0;    ///< azimuth of the camera around the model, its own frame
  double theta_deg = 0;  ///< 0: camera straight above the model, 90: level with it
  /// The instance's compass heading, degrees: with the sun fixed in the
  /// world, the side of the model it lights (the tables' heading_deg).
  double heading_deg = 0;
};

/// `center_m` and `radius_m` are the model's bounding sphere in its own
/// metres (Model::center, Model::bounding_radius); the instance's heading
/// and scale apply. `height_px`: image height.
InstanceView view_instance(const Camera& camera, int height_px, const ObjectInstance& instance,
                           glm::dvec3 center_m, double radius_m);

}  // namespace terrasprite
