// SPDX-License-Identifier: MIT
#include "viewer/path_recorder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/common/input_file.h"

namespace terrasprite::viewer {

void PathRecorder::offer(double t_s, const Camera& c) {
  if (keys_.empty() || t_s >= keys_.back().first + every_s_) keys_.emplace_back(t_s, c);
}

void PathRecorder::close(double t_s, const Camera& c) {
  if (keys_.empty() || t_s > keys_.back().first + 1e-3)
    keys_.emplace_back(t_s, c);
  else
    keys_.back().second = c;
}

nlohmann::json PathRecorder::json() const {
  nlohmann::json keys = nlohmann::json::array();
  for (const auto& [t, c] : keys_)
    keys.push_back({{"t", t},
                    {"position", {c.position.x, c.position.y, c.position.z}},
                    {"yaw_deg", c.yaw_deg},
                    {"pitch_deg", c.pitch_deg},
                    {"roll_deg", c.roll_deg},
                    {"fov_deg", c.fov_y_deg}});
  return {{"generator", generator_name()}, {"keyframes", keys}};
}

void PathRecorder::write(const std::string& file, OutputPolicy policy) const {
  write_output_file(file, policy, json().dump(2) + "\n");
}

PathPlayer::PathPlayer(const std::string& file, const Heightfield& heights, double aspect) {
  // Two passes: the file's time span, then samples at 100 per second of it.
  nlohmann::json j = nlohmann::json::parse(read_input_text(file, "path file"), nullptr, false);
  double t0 = 0, t1 = 0;
  if (!j.is_discarded() && j.is_object() && j.contains("keyframes") && j["keyframes"].is_array() &&
      !j["keyframes"].empty()) {
    const auto t_of = [](const nlohmann::json& k) {
      return k.is_object() && k.contains("t") && k["t"].is_number() ? k["t"].get<double>() : 0.0;
    };
    t0 = t_of(j["keyframes"].front());
    t1 = t_of(j["keyframes"].back());
  }
  duration_ = std::max(0.0, t1 - t0);
  const int frames = std::clamp(int(std::ceil(duration_ * 100)) + 1, 1, 1000000);
  samples_ = load_path_file(file, heights, frames, aspect);  // validates, throws InputError
}

Camera PathPlayer::camera_at(double t_s) const {
  if (samples_.size() == 1 || duration_ <= 0) return samples_.front();
  const double u = std::clamp(t_s / duration_, 0.0, 1.0) * double(samples_.size() - 1);
  return samples_[std::size_t(std::lround(u))];
}

}  // namespace terrasprite::viewer
