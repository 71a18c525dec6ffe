// SPDX-License-Identifier: MIT
#include "viewer/run_stats.h"

#include <algorithm>

#include "terrasprite/common/stats.h"

namespace terrasprite::viewer {

nlohmann::json stats_json(const RunStats& s) {
  const double p50 = percentile(s.frame_ms, 50), p99 = percentile(s.frame_ms, 99);
  std::vector<double> lat;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : s.events) {
    events.push_back({{"t", e.t}, {"latency_ms", e.latency_ms}});
    if (e.latency_ms >= 0) lat.push_back(e.latency_ms);
  }
  auto pose = [](const Camera& c) {
    return nlohmann::json{{"position", {c.position.x, c.position.y, c.position.z}},
                          {"yaw_deg", c.yaw_deg},
                          {"pitch_deg", c.pitch_deg}};
  };
  auto rate = [](double ms) { return ms > 0 ? 1000.0 / ms : 0.0; };
  nlohmann::json compared = nlohmann::json::array();
  for (const auto& c : s.comparisons)
    compared.push_back({{"mode", to_string(c.mode)}, {"psnr", c.psnr}, {"ssim", c.ssim}, {"flip", c.flip}});
  return {
      {"mode", to_string(s.mode)},
      {"size", {s.width, s.height}},
      {"frames", s.frames},
      {"fps_median", rate(p50)},
      {"fps_low_1pct", rate(p99)},
      {"frame_ms_p50", p50},
      {"frame_ms_p99", p99},
      {"render_ms_p50", percentile(s.render_ms, 50)},
      {"latency_ms_p95", percentile(lat, 95)},
      {"latency_ms_max", lat.empty() ? 0.0 : *std::max_element(lat.begin(), lat.end())},
      {"events", events},
      {"camera_start", pose(s.camera_start)},
      {"camera_end", pose(s.camera_end)},
      {"classes", s.classes},
      {"keyframes_landed", s.keyframes_landed},
      {"keyframe_ms_p50", percentile(s.keyframe_ms, 50)},
      {"keyframe_ms_max",
       s.keyframe_ms.empty() ? 0.0 : *std::max_element(s.keyframe_ms.begin(), s.keyframe_ms.end())},
      {"comparisons", compared}};
}

}  // namespace terrasprite::viewer
