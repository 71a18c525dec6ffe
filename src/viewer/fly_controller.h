// SPDX-License-Identifier: MIT
// Flying a camera from input events: fly (WASD / arrows, mouse look, Q/E up
// and down, wheel or +/- for speed) and orbit around a picked ground point.
// The camera keeps a minimum clearance above the ground and stays near the
// terrain unless told otherwise.
#pragma once
#include <set>

#include "terrasprite/camera/camera.h"
#include "terrasprite/terrain/heightfield.h"
#include "viewer/input_event.h"

namespace terrasprite::viewer {

/// Bounds of the flying speed (m/s) whatever the wheel and +/- do, and of the clearance (m).
constexpr double kMinSpeedMps = 0.01, kMaxSpeedMps = 1e6, kMaxClearanceM = 1e5;

struct FlyOptions {
  /// Flying speed, m/s. 0: follows the height above the ground (auto_speed_mps).
  double speed_mps = 0;
  double look_deg_per_px = 0.15;  ///< mouse look sensitivity
  double turn_deg_per_s = 60;     ///< arrow-key turn rate
  double clearance_m = 0;         ///< minimum height above ground; 0: 0.005 x extent
  bool bounded = true;  ///< keep over the terrain's extent x 1.5 and below 2 extents above its top
};

/// The default flying speed at `agl_m` metres above the ground over a terrain
/// `extent_m` across: half the height above ground per second (so the ground
/// below crosses the view at the same angular rate at any height), at least
/// 5 m/s and at most 2% of the extent per second.
double auto_speed_mps(double agl_m, double extent_m);

/// Turns events into camera motion. Key bindings (GLFW codes): W/S or UP/DOWN
/// forward/back, A/D strafe, LEFT/RIGHT turn, Q up, E down, +/- or wheel speed
/// x/÷ 1.25 (within kMinSpeedMps..kMaxSpeedMps), SHIFT fast (x4), mouse look (yaw, pitch), O orbit
/// around the ground point at the view centre (mouse and A/D circle, W/S move in and out), R reset
/// to the start view. The heightfield must outlive the controller.
class FlyController {
 public:
  FlyController(const Heightfield& heights, const Camera& start, FlyOptions options = {});

  void handle(const InputEvent& e);  ///< key, mouse, wheel; others are ignored
  /// Advances the motion of held keys by `dt_s` seconds and applies the
  /// clearance and bounds.
  void update(double dt_s);

  const Camera& camera() const { return camera_; }
  void set_camera(const Camera& c);  ///< e.g. from path playback; clearance applied
  void reset();
  bool orbiting() const { return orbit_; }
  /// The current speed: the fixed one, or auto_speed_mps times the +/- factor.
  double speed_mps() const;
  double clearance_m() const { return clearance_; }
  /// Where the view ray through the image centre meets the ground (or the
  /// point straight below the camera when it meets none).
  glm::dvec3 pick_centre() const;

 private:
  bool held(int key) const { return held_.count(key) > 0; }
  void toggle_orbit();
  void scale_speed(double f);
  void constrain();
  void set_speed(double s);

  const Heightfield& heights_;
  Camera start_, camera_;
  FlyOptions options_;
  double speed_ = 0;         // fixed speed, m/s; 0: auto
  double speed_factor_ = 1;  // +/- and wheel on the auto speed
  double clearance_ = 0, min_height_ = 0, ceiling_ = 0;
  std::set<int> held_;
  bool orbit_ = false;
  glm::dvec3 pivot_{0.0};
};

}  // namespace terrasprite::viewer
