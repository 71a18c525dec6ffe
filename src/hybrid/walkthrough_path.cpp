// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/walkthrough_path.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"

namespace terrasprite {

std::vector<PathCheckpoint> checkpoints_of(std::string_view json_text, const std::string& name,
                                           int frames) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json_text);
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{}: not JSON ({})", name, e.what()));
  }
  std::vector<PathCheckpoint> out;
  if (!doc.is_object() || !doc.contains("checkpoints")) return out;
  double t0 = INFINITY, t1 = -INFINITY;
  if (doc.contains("keyframes") && doc["keyframes"].is_array())
    for (const auto& k : doc["keyframes"])
      if (k.is_object() && k.contains("t") && k["t"].is_number()) {
        t0 = std::min(t0, k["t"].get<double>());
        t1 = std::max(t1, k["t"].get<double>());
      }
  if (!doc["checkpoints"].is_array())
    throw InputError(fmt::format("{}: \"checkpoints\" must be an array", name));
  for (std::size_t i = 0; i < doc["checkpoints"].size(); ++i) {
    const auto& c = doc["checkpoints"][i];
    const std::string where = fmt::format("{}: checkpoints[{}]", name, i);
    if (!c.is_object() || !c.contains("name") || !c["name"].is_string() ||
        c["name"].get<std::string>().empty())
      throw InputError(where + ": needs a non-empty \"name\"");
    if (!c.contains("t") || !c["t"].is_number() || !std::isfinite(c["t"].get<double>()))
      throw InputError(where + ": needs a number \"t\" (seconds)");
    const double t = c["t"].get<double>();
    if (!(t >= t0 && t <= t1))
      throw InputError(
          fmt::format("{}: t {} is outside the keyframes' span [{}, {}]", where, t, t0, t1));
    const int frame = t1 > t0 ? int(std::lround((t - t0) / (t1 - t0) * (frames - 1))) : 0;
    out.push_back({c["name"].get<std::string>(), t, frame});
  }
  return out;
}

std::string walkthrough_path_json(const Heightfield& h,
                                  const std::function<double(double, double)>& ground) {
  const auto z = [&](double x, double y) { return ground ? ground(x, y) : double(h.sample(x, y)); };
  struct Key {
    double t, x, y, above, tx, ty, target_above;
    const char* checkpoint;
  };
  // Human height between the objects, low altitude over the centre.
  const Key keys[] = {
      {0, -260, -250, 1.7, -200, -190, 1.5, "A"}, {8, -190, -170, 1.7, -130, -100, 1.5, nullptr},
      {16, -120, -95, 1.7, -60, -40, 1.0, "B"},   {24, -50, -40, 12, 20, 20, 0, nullptr},
      {32, 10, 15, 30, 90, 70, 0, "C"},           {40, 80, 60, 12, 150, 110, 0, nullptr},
      {48, 140, 110, 1.7, 200, 160, 1.5, "D"},    {56, 200, 170, 20, 260, 120, 0, nullptr},
      {64, 250, 240, 40, 0, 0, 0, "E"},
  };
  nlohmann::json kf = nlohmann::json::array(), cp = nlohmann::json::array();
  for (const Key& k : keys) {
    kf.push_back({{"t", k.t},
                  {"position", {k.x, k.y, z(k.x, k.y) + k.above}},
                  {"target", {k.tx, k.ty, z(k.tx, k.ty) + k.target_above}},
                  {"fov_deg", 60}});
    if (k.checkpoint) cp.push_back({{"name", k.checkpoint}, {"t", k.t}});
  }
  return nlohmann::json{{"keyframes", kf}, {"checkpoints", cp}}.dump(2);
}

void keep_above_ground(std::vector<Camera>& path,
                       const std::function<double(double, double)>& ground, double min_eye_m) {
  for (Camera& c : path) {
    const double z = ground(c.position.x, c.position.y);
    c.position.z = std::max(c.position.z, z + min_eye_m);
    c.near_m = std::min(c.near_m, std::max(0.05, 0.125 * (c.position.z - z)));
  }
}

}  // namespace terrasprite
