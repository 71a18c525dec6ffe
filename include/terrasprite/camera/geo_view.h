// SPDX-License-Identifier: MIT
// Cameras placed geographically: the look-at form of Cesium's flyTo and
// osgEarth's Viewpoint (target, range, heading, pitch) on a terrain with a CRS.
#pragma once
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// A view of a ground point: the target at (lon, lat) (WGS 84 degrees) on the
/// ground; the eye `range_m` metres from it, back along the view direction.
/// The view direction's heading is clockwise from north (0 = looking north,
/// 90 = looking east), its pitch the elevation (negative looks down, -90
/// straight down).
struct LookAtView {
  double lon = 0, lat = 0;
  double range_m = 1000;
  double heading_deg = 0;
  double pitch_deg = -30;
};

/// The camera of `v` on `h` (near/far fitted). Throws InputError (naming
/// the --look-at, --range or --pitch option) when `h` has no CRS, the target
/// is not on the terrain, the range is not within 1 m .. 1e7 m, the pitch not
/// within [-90, 90], the heading not finite, or the eye below the ground.
Camera look_at_camera(const LookAtView& v, const Heightfield& h, double aspect,
                      double fov_y_deg = 60.0);

/// A flight starting at the view `v`: `frames` frames (>= 1) orbiting the
/// target once, clockwise seen from above, at v's range and pitch (the eye
/// kept above the ground). One frame is look_at_camera(v).
std::vector<Camera> look_at_orbit(const LookAtView& v, const Heightfield& h, int frames,
                                  double aspect, double fov_y_deg = 60.0);

}  // namespace terrasprite
