// SPDX-License-Identifier: MIT
// Perspective camera shared by every renderer (GL and voxel).
#pragma once
#include <glm/glm.hpp>
#include <numbers>

namespace terrasprite {

// Degrees to radians: camera angles are stored in degrees.
inline constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;

struct Heightfield;

/// A perspective camera in world metres (x east, y north, z up).
/// Orientation: yaw is the compass heading of the view direction (0 = north,
/// 90 = east), pitch the elevation of the view direction (-90 = straight down),
/// roll a rotation about the view direction (positive tilts the image's up
/// vector towards the right, i.e. the horizon turns anticlockwise in the image).
/// Projection follows OpenGL: right-handed eye space looking down -z, the
/// vertical field of view spans the image height, pixel centres at +0.5.
struct Camera {
  glm::dvec3 position{0.0};
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;
  double roll_deg = 0.0;
  double fov_y_deg = 60.0;  ///< vertical field of view, degrees (0, 180)
  double aspect = 1.0;      ///< width / height
  double near_m = 1.0;      ///< near clip distance, metres (> 0)
  double far_m = 1e5;       ///< far clip distance, metres (> near_m)

  /// Camera at `eye` looking at `target`. When the view is vertical the yaw
  /// is `yaw_hint_deg` (the heading the image's top points to).
  static Camera look_at(glm::dvec3 eye, glm::dvec3 target, double fov_y_deg, double aspect,
                        double yaw_hint_deg = 0.0);

  glm::dvec3 forward() const;  ///< unit view direction
  glm::dvec3 right() const;    ///< unit image-right direction (roll applied)
  glm::dvec3 up() const;       ///< unit image-up direction (roll applied)
  glm::dmat4 view() const;     ///< world -> eye
  /// Eye -> clip, OpenGL conventions (z in [-1, 1], near -> -1).
  glm::dmat4 projection() const;
  glm::dmat4 view_projection() const { return projection() * view(); }
  /// Angle of one pixel at the image centre, radians, for an image `height_px` tall.
  double pixel_angle(int height_px) const;
  /// World-space direction through pixel (px, py) (pixel units, y down, centres at +0.5).
  glm::dvec3 ray_direction(double px, double py, int width, int height) const;
};

/// Sets near/far so the whole terrain (with exaggerated heights) is inside the
/// far plane and the near plane is as far out as the nearest terrain allows.
void fit_clip_planes(Camera& camera, const Heightfield& heights);

}  // namespace terrasprite
