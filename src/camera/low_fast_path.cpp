// SPDX-License-Identifier: MIT
// A low, fast flight for the warp's hard cases: about 150 m above the ground
// at 200 m/s, 60 frames a second, weaving gently (banked turns) northwards
// across the terrain centre, looking a little down.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kSpeed = 200.0;      // m/s
constexpr double kRate = 60.0;        // frames per second
constexpr double kClearance = 150.0;  // m above the highest ground near the eye

// Ground clearance: the highest ground within 300 m ahead and 100 m behind
// along the track, so the flight climbs before a ridge rather than into it.
double ground_ahead(const Heightfield& h, double x0, double y0, double dx, double dy) {
  double g = -1e30;
  for (double s = -100.0; s <= 300.0; s += 25.0)
    g = std::max(g, double(h.sample(x0 + s * dx, y0 + s * dy)));
  return g;
}
}  // namespace

std::vector<Camera> low_fast_path(const Heightfield& h, int frames, double aspect,
                                  double fov_y_deg) {
  if (frames < 1) throw InputError(fmt::format("frames {}: must be at least 1", frames));
  const double E = h.extent();
  // Track: x = A sin(2 pi s / L), y = y0 + s (s = distance flown northwards).
  const double A = 0.01 * E, L = 0.25 * E, y0 = -0.2 * E;
  auto track = [&](double s, double& x, double& y, double& dx, double& dy, double& curv) {
    const double k = 2 * kPi / L;
    x = A * std::sin(k * s);
    y = y0 + s;
    const double xp = A * k * std::cos(k * s), xpp = -A * k * k * std::sin(k * s);
    const double n = std::hypot(xp, 1.0);
    dx = xp / n;
    dy = 1.0 / n;
    curv = xpp / (n * n * n);  // signed: positive turns left (west)
  };
  std::vector<Camera> path;
  path.reserve(frames);
  double z_prev = 0;
  for (int f = 0; f < frames; ++f) {
    const double s = kSpeed * f / kRate;
    double x, y, dx, dy, curv;
    track(s, x, y, dx, dy, curv);
    double z = ground_ahead(h, x, y, dx, dy) + kClearance;
    // Climb at once, sink gently (at most 2 m a frame), so the view does not bob.
    if (f > 0 && z < z_prev) z = std::max(z, z_prev - 2.0);
    z_prev = z;
    Camera c;
    c.position = {x, y, z};
    c.yaw_deg = std::atan2(dx, dy) * 180.0 / kPi;
    c.pitch_deg = -8.0;
    // Coordinated turn: bank = atan(v^2 kappa / g), right wing down turning right.
    c.roll_deg = std::clamp(std::atan(kSpeed * kSpeed * curv / 9.81) * 180.0 / kPi, -30.0, 30.0);
    c.fov_y_deg = fov_y_deg;
    c.aspect = aspect;
    fit_clip_planes(c, h);
    path.push_back(c);
  }
  return path;
}

}  // namespace terrasprite
