// SPDX-License-Identifier: MIT
#include "terrasprite/report/terrain_json.h"

#include <nlohmann/json.hpp>

namespace terrasprite::report {

nlohmann::json terrain_json(const TerrainInfo& t) {
  return {{"name", t.name},
          {"samples", {t.samples_x, t.samples_y}},
          {"quads", {t.samples_x - 1, t.samples_y - 1}},
          {"spacing_m", {t.spacing_x, t.spacing_y}},
          {"extent_m", {(t.samples_x - 1) * t.spacing_x, (t.samples_y - 1) * t.spacing_y}},
          {"height_min", t.height_min},
          {"height_max", t.height_max},
          {"texture", t.texture},
          // null: the input's own grid; else its samples before --resample
          {"resampled_from", t.resampled_from
                                 ? nlohmann::json{t.resampled_from->first, t.resampled_from->second}
                                 : nlohmann::json(nullptr)}};
}

nlohmann::json terrain_json(const Terrain& t) {
  return terrain_json(terrain_info(t));
}

}  // namespace terrasprite::report
