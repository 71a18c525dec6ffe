// SPDX-License-Identifier: MIT
// Viewpoint prediction for asynchronous keyframes (the future work of Chen et
// al. 1999, section 5): the camera's recent motion extrapolated to the frame
// a keyframe requested now will land on.
#pragma once
#include <deque>

#include "terrasprite/camera/camera.h"
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// Keeps the last few cameras (one per displayed frame) and extrapolates
/// their motion linearly: position, yaw (wrapped), pitch and roll move on by
/// their mean per-frame change over the history. Field of view and aspect are
/// the newest camera's; the clip planes are refitted to the terrain.
class CameraPredictor {
 public:
  /// `history`: how many past cameras the velocity is averaged over (>= 2).
  explicit CameraPredictor(int history = 4) : history_(history) {}
  void observe(const Camera& camera);
  void clear() { cameras_.clear(); }
  /// The camera `frames_ahead` displayed frames after the newest observed one
  /// (the newest itself with fewer than two observed). Needs one observed.
  Camera predict(double frames_ahead, const Heightfield& heights) const;

 private:
  int history_;
  std::deque<Camera> cameras_;
};

}  // namespace terrasprite
