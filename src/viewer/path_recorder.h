// SPDX-License-Identifier: MIT
// Recording a flight as a camera path file (the `--path` JSON schema) and
// playing such a file back in real time.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/output/output_file.h"
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite::viewer {

/// Keeps a keyframe every `every_s` seconds of flight (and the last pose on
/// finish), so the file replays the flight with `--path` or `view --play`.
class PathRecorder {
 public:
  explicit PathRecorder(double every_s = 0.5) : every_s_(every_s) {}
  /// Offers the pose at `t_s` seconds since recording began (non-decreasing).
  void offer(double t_s, const Camera& c);
  /// Keeps the pose at `t_s` whatever the interval (e.g. the end of a flight).
  void close(double t_s, const Camera& c);
  std::size_t size() const { return keys_.size(); }
  /// {"generator", "keyframes": [{"t", "position", "yaw_deg", "pitch_deg", "roll_deg", "fov_deg"}]}
  nlohmann::json json() const;
  /// Writes json() by the output-file rules (write_output_file); throws
  /// InputError naming the file on failure or when it may not be replaced.
  void write(const std::string& file, OutputPolicy policy) const;

 private:
  double every_s_;
  std::vector<std::pair<double, Camera>> keys_;
};

/// A path file flown in real time: camera_at(t) for t in [0, duration()].
class PathPlayer {
 public:
  /// Throws InputError naming the file when it is not a valid path file.
  PathPlayer(const std::string& file, const Heightfield& heights, double aspect);
  double duration() const { return duration_; }
  Camera camera_at(double t_s) const;  ///< clamped to the path's ends

 private:
  std::vector<Camera> samples_;  // uniform in t, 100 per second
  double duration_ = 0;
};

}  // namespace terrasprite::viewer
