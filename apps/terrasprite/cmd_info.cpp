// SPDX-License-Identifier: MIT
// terrasprite info: what was loaded (size, spacing, extent, heights, nodata).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <optional>

#include "cli_common.h"
#include "commands.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/terrain/geo_frame.h"

namespace terrasprite::cli {

namespace {

// Share of this grid's samples that were nodata (a resampled grid: those
// nearest a nodata source sample).
double filled_fraction(const Heightfield& h) {
  if (h.voids.empty()) return 0.0;
  return double(std::count(h.voids.begin(), h.voids.end(), std::uint8_t{1})) /
         double(h.voids.size());
}

const char* fill_method_text(NodataFill f) {
  switch (f) {
    case NodataFill::kGdal:
      return "GDALFillNodata (inverse distance)";
    default:
      return "AMLE (least steep surface from the rim)";
  }
}

nlohmann::json nodata_json(const Heightfield& h) {
  return {{"count", h.nodata_count},
          {"filled_fraction", filled_fraction(h)},
          {"fill_method", to_string(h.fill_method)}};
}

std::string nodata_text(const Heightfield& h) {
  if (h.nodata_count == 0) return "no nodata cells";
  if (h.fill_method == NodataFill::kNone)
    return fmt::format(
        "{} nodata cells ({:.1f}% of the grid) left as holes (--fill none; the renderers draw "
        "every cell, so they take --fill amle or gdal)",
        h.nodata_count, 100 * filled_fraction(h));
  return fmt::format("{} nodata cells ({:.1f}% of the grid) filled by {}", h.nodata_count,
                     100 * filled_fraction(h), fill_method_text(h.fill_method));
}

// Where a terrain with a CRS lies: its CRS and lon/lat box (what --look-at
// and lon/lat path keys take).
struct Place {
  std::string crs;
  std::array<double, 4> lonlat_box;  ///< west, south, east, north
};

std::optional<Place> place_of(const Heightfield& h) {
  if (!has_crs(h)) return std::nullopt;
  const GeoFrame f(h, "info");
  return Place{f.crs_name(), f.lonlat_box()};
}

nlohmann::json place_json(const std::optional<Place>& p) {
  if (!p) return nullptr;
  return {{"crs", p->crs}, {"lonlat_box", p->lonlat_box}};
}

std::string place_text(const std::optional<Place>& p) {
  if (!p) return "no CRS: places are given in metres from the centre";
  const auto& b = p->lonlat_box;
  return fmt::format("CRS {}; longitude {:.5f} .. {:.5f}, latitude {:.5f} .. {:.5f} (WGS 84)",
                     p->crs, b[0], b[2], b[1], b[3]);
}

}  // namespace

void add_info(CLI::App& app, const OutputPolicy& policy) {
  auto* cmd =
      app.add_subcommand("info", "describe a terrain: size, spacing, extent, height range, nodata");
  struct Opts {
    TerrainOptions terrain;
    std::string json;
  };
  auto o = std::make_shared<Opts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--json", o->json, "write the description as JSON");
  cmd->callback([o, &policy] {
    check_outputs(policy, "", {o->json});
    Terrain t = load_terrain_verbose(o->terrain);
    const Heightfield& h = t.heights;
    const std::optional<Place> place = place_of(h);
    nlohmann::json j = {{"name", h.name},
                        {"samples", {h.width, h.height}},
                        {"spacing_m", {h.spacing_x, h.spacing_y}},
                        {"extent_m", {h.extent_x(), h.extent_y()}},
                        {"height_min", h.min_height()},
                        {"height_max", h.max_height()},
                        {"nodata_count", h.nodata_count},
                        {"nodata", nodata_json(h)},
                        {"resampled_to", nullptr},
                        {"texture", t.texture_name},
                        {"texture_size", {t.texture.width, t.texture.height}},
                        {"georeferenced", h.geo.has_value()},
                        {"place", place_json(place)}};
    if (h.resampled_to) j["resampled_to"] = {h.resampled_to->first, h.resampled_to->second};
    if (!o->json.empty()) report::write_json(j, o->json, policy);
    fmt::print("{}: {} x {} samples, spacing {:.3f} x {:.3f} m, extent {:.1f} x {:.1f} m\n", h.name,
               h.width, h.height, h.spacing_x, h.spacing_y, h.extent_x(), h.extent_y());
    fmt::print("heights {:.2f} .. {:.2f} m, {}{}\n", h.min_height(), h.max_height(), nodata_text(h),
               h.resampled_to ? fmt::format(", resampled to {} x {}", h.resampled_to->first,
                                            h.resampled_to->second)
                              : "");
    fmt::print("{}\n", place_text(place));
  });
}

}  // namespace terrasprite::cli
