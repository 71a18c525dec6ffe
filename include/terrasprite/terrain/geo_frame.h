// SPDX-License-Identifier: MIT
// Geographic places on a terrain: WGS 84 longitude/latitude to the terrain's
// world metres (x east, y north from the grid's centre), through the raster's
// own CRS.
#pragma once
#include <array>
#include <memory>
#include <string>

#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// A point in world metres on the ground plane.
struct WorldXY {
  double x = 0, y = 0;
};

/// How far outside the terrain's footprint a place may lie, in units of the
/// footprint's size on each axis: targets must be on the terrain, eyes may be
/// up to one extent beyond its edges (an overview flies outside it).
enum class GeoMargin { kOnTerrain, kNearTerrain };

/// WGS 84 (EPSG:4326, longitude first) to the world metres of one terrain:
/// GDAL's coordinate transformation to the raster's CRS, then the raster's
/// geotransform to the grid (sample centres; a resampled grid keeps the
/// source's corner samples), then the grid to world metres.
class GeoFrame {
 public:
  /// The frame of `h`; throws InputError naming `what` (the option or key
  /// asking) when `h` has no georeferencing with a CRS.
  GeoFrame(const Heightfield& h, const std::string& what);
  ~GeoFrame();
  GeoFrame(GeoFrame&&) noexcept;
  GeoFrame& operator=(GeoFrame&&) noexcept;

  /// World metres of (lon, lat) in degrees. Throws InputError naming `what`
  /// when either is not finite, lat is outside [-90, 90], lon outside
  /// [-180, 360], the CRS cannot take the point, or it lies outside `margin`.
  WorldXY world_of(double lon, double lat, GeoMargin margin, const std::string& what) const;
  /// Longitude and latitude (degrees) of world metres (x, y).
  std::pair<double, double> lonlat_of(WorldXY p) const;
  /// The corner samples' lon,lat, for messages.
  std::string footprint_text() const;
  /// The raster's CRS as a user names it: "EPSG:4326 (WGS 84)", or its name
  /// alone when it has no authority code.
  std::string crs_name() const;
  /// The smallest longitude/latitude box holding the terrain's corners and
  /// edge midpoints: {west, south, east, north}, degrees.
  std::array<double, 4> lonlat_box() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// True when `h` carries a CRS that GeoFrame can use.
bool has_crs(const Heightfield& h);

}  // namespace terrasprite
