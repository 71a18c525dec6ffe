// SPDX-License-Identifier: MIT
#include "look_at_options.h"

#include <fmt/format.h>

#include <cstdio>

#include "terrasprite/common/error.h"

namespace terrasprite::cli {

CLI::Option* add_look_at_options(CLI::App& cmd, LookAtOptions& o) {
  CLI::Option* look = cmd.add_option(
      "--look-at", o.look_at,
      "LON,LAT (WGS 84 degrees) of a ground point to look at; needs a terrain with a CRS. The "
      "eye is --range metres back along the view (Cesium flyTo / osgEarth Viewpoint form)");
  cmd.add_option("--range", o.range_m,
                 "with --look-at: metres from the eye to the target (default: a fifth of the "
                 "terrain's extent)");
  cmd.add_option("--heading", o.heading_deg,
                 "with --look-at: view direction, degrees clockwise from north (default 0)");
  cmd.add_option("--pitch", o.pitch_deg,
                 "with --look-at: view elevation, degrees, negative looks down (default -30)");
  return look;
}

std::optional<LookAtView> parse_look_at(const LookAtOptions& o, const Heightfield& h) {
  if (o.look_at.empty()) {
    if (o.range_m || o.heading_deg || o.pitch_deg)
      throw InputError("--range, --heading and --pitch need --look-at LON,LAT");
    return std::nullopt;
  }
  LookAtView v;
  char extra = 0;
  if (std::sscanf(o.look_at.c_str(), "%lf,%lf%c", &v.lon, &v.lat, &extra) != 2)
    throw InputError(fmt::format(
        "--look-at {}: expected LON,LAT in degrees (e.g. 138.7274,35.3606)", o.look_at));
  v.range_m = o.range_m.value_or(0.2 * h.extent());
  v.heading_deg = o.heading_deg.value_or(0.0);
  v.pitch_deg = o.pitch_deg.value_or(-30.0);
  return v;
}

}  // namespace terrasprite::cli
