// SPDX-License-Identifier: MIT
// The JSON description of a terrain every study's document carries.
#pragma once
#include <nlohmann/json_fwd.hpp>

#include "terrasprite/experiment/terrain_info.h"

namespace terrasprite::report {

/// {name, samples, quads, spacing_m, extent_m, height_min, height_max, texture}.
nlohmann::json terrain_json(const TerrainInfo& t);

}  // namespace terrasprite::report
