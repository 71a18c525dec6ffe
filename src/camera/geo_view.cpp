// SPDX-License-Identifier: MIT
// Look-at views (target, range, heading, pitch) and the orbit flight from one.
#include "terrasprite/camera/geo_view.h"

#include <fmt/format.h>

#include <cmath>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/geo_frame.h"

namespace terrasprite {
namespace {

constexpr double kMinRangeM = 1.0, kMaxRangeM = 1e7;

void check_view(const LookAtView& v) {
  if (!(v.range_m >= kMinRangeM && v.range_m <= kMaxRangeM))
    throw InputError(fmt::format("--range {}: must be within {:g} .. {:g} m", v.range_m, kMinRangeM,
                                 kMaxRangeM));
  if (!(v.pitch_deg >= -90 && v.pitch_deg <= 90))
    throw InputError(fmt::format(
        "--pitch {}: must be within -90 .. 90 degrees (negative looks down)", v.pitch_deg));
  if (!std::isfinite(v.heading_deg))
    throw InputError(
        fmt::format("--heading {}: must be a finite number of degrees", v.heading_deg));
}

// The eye `range` metres back from `target` along the view (heading, pitch).
glm::dvec3 eye_of(const glm::dvec3& target, double range, double heading_deg, double pitch_deg) {
  const double hd = heading_deg * kRadiansPerDegree, p = pitch_deg * kRadiansPerDegree;
  const glm::dvec3 forward(std::sin(hd) * std::cos(p), std::cos(hd) * std::cos(p), std::sin(p));
  return target - range * forward;
}

Camera camera_at(const glm::dvec3& eye, double heading_deg, double pitch_deg, double fov_y_deg,
                 double aspect, const Heightfield& h) {
  Camera c;
  c.position = eye;
  c.yaw_deg = std::remainder(heading_deg, 360.0);
  c.pitch_deg = pitch_deg;
  c.fov_y_deg = fov_y_deg;
  c.aspect = aspect;
  fit_clip_planes(c, h);
  return c;
}

glm::dvec3 target_of(const LookAtView& v, const Heightfield& h) {
  const GeoFrame frame(h, "--look-at");
  const WorldXY p = frame.world_of(v.lon, v.lat, GeoMargin::kOnTerrain, "--look-at");
  return {p.x, p.y, h.sample(p.x, p.y)};
}

}  // namespace

Camera look_at_camera(const LookAtView& v, const Heightfield& h, double aspect, double fov_y_deg) {
  check_view(v);
  const glm::dvec3 target = target_of(v, h);
  const glm::dvec3 eye = eye_of(target, v.range_m, v.heading_deg, v.pitch_deg);
  const double ground = h.sample(eye.x, eye.y);
  if (eye.z < ground)
    throw InputError(fmt::format(
        "--pitch {}: the eye would be {:.0f} m below the ground at range {:g} m (look down more "
        "or shorten --range)",
        v.pitch_deg, ground - eye.z, v.range_m));
  return camera_at(eye, v.heading_deg, v.pitch_deg, fov_y_deg, aspect, h);
}

std::vector<Camera> look_at_orbit(const LookAtView& v, const Heightfield& h, int frames,
                                  double aspect, double fov_y_deg) {
  if (frames < 1) throw InputError(fmt::format("frames {}: must be at least 1", frames));
  std::vector<Camera> path{look_at_camera(v, h, aspect, fov_y_deg)};
  const glm::dvec3 target = target_of(v, h);
  const double clearance = 0.002 * h.extent();
  for (int f = 1; f < frames; ++f) {
    const double heading = v.heading_deg + 360.0 * f / frames;
    glm::dvec3 eye = eye_of(target, v.range_m, heading, v.pitch_deg);
    eye.z = std::max(eye.z, double(h.sample(eye.x, eye.y)) + clearance);
    const Camera look = Camera::look_at(eye, target, fov_y_deg, aspect, heading);
    path.push_back(camera_at(eye, look.yaw_deg, look.pitch_deg, fov_y_deg, aspect, h));
  }
  return path;
}

}  // namespace terrasprite
