// SPDX-License-Identifier: MIT
// A terrain as every report describes it.
#pragma once
#include <nlohmann/json_fwd.hpp>

#include "terrasprite/terrain/terrain_info.h"

namespace terrasprite::report {

/// {name, samples, quads, spacing_m, extent_m, height_min, height_max, texture}.
nlohmann::json terrain_json(const TerrainInfo& t);
nlohmann::json terrain_json(const Terrain& t);

}  // namespace terrasprite::report
