// SPDX-License-Identifier: MIT
#include "viewer/fly_controller.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

namespace terrasprite::viewer {

namespace {

glm::dvec3 flat_forward(double yaw_deg) {
  const double y = glm::radians(yaw_deg);
  return {std::sin(y), std::cos(y), 0.0};  // yaw 0 = north (+y), 90 = east (+x)
}

}  // namespace

double auto_speed_mps(double agl_m, double extent_m) {
  const double top = std::max(5.0, 0.02 * extent_m);
  return std::clamp(0.5 * agl_m, 5.0, top);
}

double FlyController::speed_mps() const {
  if (speed_ > 0) return speed_;
  const glm::dvec3& p = camera_.position;
  const double agl = p.z - heights_.sample(p.x, p.y);
  return std::clamp(speed_factor_ * auto_speed_mps(agl, std::max(1.0, heights_.extent())),
                    kMinSpeedMps, kMaxSpeedMps);
}

void FlyController::scale_speed(double f) {
  if (!(f > 0) || !std::isfinite(f)) return;
  if (speed_ > 0)
    set_speed(speed_ * f);
  else  // the auto speed is clamped in speed_mps; the factor stays a finite number
    speed_factor_ = std::clamp(speed_factor_ * f, 1e-9, 1e9);
}

FlyController::FlyController(const Heightfield& heights, const Camera& start, FlyOptions options)
    : heights_(heights), start_(start), camera_(start), options_(options) {
  const double e = std::max(1.0, heights.extent());
  speed_ = options.speed_mps > 0 ? std::clamp(options.speed_mps, kMinSpeedMps, kMaxSpeedMps) : 0.0;
  clearance_ = options.clearance_m > 0 ? std::min(options.clearance_m, kMaxClearanceM)
                                       : std::min(0.005 * e, kMaxClearanceM);
  min_height_ = heights.min_height();
  ceiling_ = std::max(double(heights.max_height()) + 2.0 * e, start.position.z);
  constrain();
}

void FlyController::handle(const InputEvent& e) {
  switch (e.kind) {
    case InputKind::kKey:
      if (e.action == GLFW_RELEASE) {
        held_.erase(e.key);
        return;
      }
      if (e.action == GLFW_PRESS) {
        held_.insert(e.key);
        if (e.key == GLFW_KEY_EQUAL || e.key == GLFW_KEY_KP_ADD) scale_speed(1.25);
        if (e.key == GLFW_KEY_MINUS || e.key == GLFW_KEY_KP_SUBTRACT) scale_speed(1 / 1.25);
        if (e.key == GLFW_KEY_O) toggle_orbit();
        if (e.key == GLFW_KEY_R) reset();
      }
      return;
    case InputKind::kMouse:
      camera_.yaw_deg = std::fmod(camera_.yaw_deg + e.dx * options_.look_deg_per_px + 360, 360);
      camera_.pitch_deg =
          std::clamp(camera_.pitch_deg - e.dy * options_.look_deg_per_px, -89.0, 89.0);
      if (orbit_) {  // keep the pivot at the centre: move the eye around it
        const double d = glm::length(camera_.position - pivot_);
        camera_.position = pivot_ - camera_.forward() * d;
      }
      constrain();
      return;
    case InputKind::kWheel:
      // Notches past the speed's bounds leave it at the bound: a wheel offset
      // of any size (or a NaN from a driver) never makes it unbounded.
      if (std::isfinite(e.dy)) scale_speed(std::pow(1.25, std::clamp(e.dy, -1e3, 1e3)));
      return;
    default:
      return;
  }
}

void FlyController::update(double dt_s) {
  const double boost = held(GLFW_KEY_LEFT_SHIFT) || held(GLFW_KEY_RIGHT_SHIFT) ? 4.0 : 1.0;
  const double step = speed_mps() * boost * dt_s;
  const double fwd = (held(GLFW_KEY_W) || held(GLFW_KEY_UP) ? 1.0 : 0.0) -
                     (held(GLFW_KEY_S) || held(GLFW_KEY_DOWN) ? 1.0 : 0.0);
  const double side = (held(GLFW_KEY_D) ? 1.0 : 0.0) - (held(GLFW_KEY_A) ? 1.0 : 0.0);
  const double turn = (held(GLFW_KEY_RIGHT) ? 1.0 : 0.0) - (held(GLFW_KEY_LEFT) ? 1.0 : 0.0);
  const double lift = (held(GLFW_KEY_Q) ? 1.0 : 0.0) - (held(GLFW_KEY_E) ? 1.0 : 0.0);
  if (orbit_) {
    // Circle the pivot (A/D, LEFT/RIGHT), move in and out (W/S).
    const double d = std::max(clearance_, glm::length(camera_.position - pivot_) - fwd * step);
    camera_.yaw_deg =
        std::fmod(camera_.yaw_deg - (side + turn) * options_.turn_deg_per_s * dt_s + 360.0, 360.0);
    camera_.position = pivot_ - camera_.forward() * d;
  } else {
    camera_.yaw_deg = std::fmod(camera_.yaw_deg + turn * options_.turn_deg_per_s * dt_s + 360, 360);
    const glm::dvec3 f = flat_forward(camera_.yaw_deg);
    const glm::dvec3 r{f.y, -f.x, 0.0};
    camera_.position += (f * fwd + r * side + glm::dvec3(0, 0, 1) * lift) * step;
  }
  constrain();
}

void FlyController::set_speed(double s) {
  speed_ = std::clamp(std::isfinite(s) ? s : kMaxSpeedMps, kMinSpeedMps, kMaxSpeedMps);
}

void FlyController::set_camera(const Camera& c) {
  camera_ = c;
  orbit_ = false;
  constrain();
}

void FlyController::reset() {
  camera_ = start_;
  orbit_ = false;
  constrain();
}

void FlyController::toggle_orbit() {
  orbit_ = !orbit_;
  if (orbit_) pivot_ = pick_centre();
}

glm::dvec3 FlyController::pick_centre() const {
  // March the centre ray in steps of a sample spacing up to the terrain's extent x 3.
  const glm::dvec3 d = camera_.forward();
  const double step = std::min(heights_.spacing_x, heights_.spacing_y);
  const double reach =
      3 * std::max(1.0, heights_.extent()) + std::abs(camera_.position.z - min_height_);
  for (double s = 0; s < reach; s += step) {
    const glm::dvec3 p = camera_.position + d * s;
    if (p.z <= heights_.sample(p.x, p.y)) return p;
  }
  const glm::dvec3 p = camera_.position;
  return {p.x, p.y, heights_.sample(p.x, p.y)};
}

void FlyController::constrain() {
  glm::dvec3& p = camera_.position;
  if (options_.bounded) {
    const double hx = 0.75 * std::max(1.0, heights_.extent_x());
    const double hy = 0.75 * std::max(1.0, heights_.extent_y());
    p.x = std::clamp(p.x, -hx, hx);
    p.y = std::clamp(p.y, -hy, hy);
    p.z = std::min(p.z, ceiling_);
  }
  p.z = std::max(p.z, double(heights_.sample(p.x, p.y)) + clearance_);
  fit_clip_planes(camera_, heights_);
}

}  // namespace terrasprite::viewer
