// SPDX-License-Identifier: MIT
// Linear extrapolation of the camera: the simplest predictor that follows a
// smooth flight path; a turn is caught by the next request once the keyframe
// that missed it lands (AsyncKeyframes reports how often that happens).
#include "sprite/camera_prediction.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace terrasprite {
namespace {

// b - a in degrees, wrapped to [-180, 180): a yaw through north is a small turn.
double angle_delta(double a, double b) {
  return std::remainder(b - a, 360.0);
}

}  // namespace

void CameraPredictor::observe(const Camera& camera) {
  cameras_.push_back(camera);
  while (int(cameras_.size()) > history_) cameras_.pop_front();
}

Camera CameraPredictor::predict(double frames_ahead, const Heightfield& heights) const {
  assert(!cameras_.empty());
  const Camera &oldest = cameras_.front(), &newest = cameras_.back();
  Camera c = newest;
  const double span = double(cameras_.size() - 1);
  if (span > 0) {
    const double k = frames_ahead / span;
    c.position += (newest.position - oldest.position) * k;
    c.yaw_deg += angle_delta(oldest.yaw_deg, newest.yaw_deg) * k;
    c.pitch_deg = std::clamp(c.pitch_deg + (newest.pitch_deg - oldest.pitch_deg) * k, -90.0, 90.0);
    c.roll_deg += angle_delta(oldest.roll_deg, newest.roll_deg) * k;
  }
  fit_clip_planes(c, heights);
  return c;
}

}  // namespace terrasprite
