// SPDX-License-Identifier: MIT
// `--look-at LON,LAT --range M --heading DEG --pitch DEG` for the commands
// that place a camera (render, view); the cameras are terrasprite/camera/geo_view.h.
#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "terrasprite/camera/geo_view.h"

namespace terrasprite::cli {

struct LookAtOptions {
  std::string look_at;  ///< "LON,LAT" in WGS 84 degrees; empty: not given
  std::optional<double> range_m, heading_deg, pitch_deg;
};

/// Adds the four options; returns --look-at (for excludes()).
CLI::Option* add_look_at_options(CLI::App& cmd, LookAtOptions& o);

/// The view asked for, or nothing without --look-at. Throws InputError for a
/// malformed --look-at, or --range/--heading/--pitch given without it.
/// Defaults: range a fifth of the terrain's extent, heading 0 (looking north),
/// pitch -30 (looking down).
std::optional<LookAtView> parse_look_at(const LookAtOptions& o, const Heightfield& h);

}  // namespace terrasprite::cli
