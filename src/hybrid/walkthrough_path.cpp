// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/walkthrough_path.h"

#include <algorithm>

namespace terrasprite {

KeyframePath walkthrough_path(const Heightfield& h,
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
  KeyframePath path;
  for (const Key& k : keys) {
    PathKeyframe f;
    f.t = k.t;
    f.position = {k.x, k.y, z(k.x, k.y) + k.above};
    f.target = glm::dvec3(k.tx, k.ty, z(k.tx, k.ty) + k.target_above);
    f.fov_deg = 60;
    path.keyframes.push_back(f);
    if (k.checkpoint) path.checkpoints.push_back({k.checkpoint, k.t, 0});
  }
  return path;
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
