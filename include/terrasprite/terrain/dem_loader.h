// SPDX-License-Identifier: MIT
// Height rasters read through GDAL, and the RGB height encodings of web tiles.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "terrasprite/terrain/heightfield.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

/// Reads a height raster: any GDAL raster (GeoTIFF, SRTM .hgt, DTED, ASCII
/// grid, VRT, 16-bit PNG, ...), or an 8-bit RGB PNG in terrain-RGB/Terrarium
/// encoding. Uses these fields of `o`: dem, z_scale, spacing, nodata, fill, encoding.
/// Spacing comes from the geotransform (projected units converted to metres;
/// geographic degrees converted at the raster's centre latitude) unless
/// `o.spacing` is set; a raster without georeferencing gets 30 m and a warning.
/// Nodata cells are filled from their neighbours as `o.fill` says (AMLE,
/// GDAL, or AMLE marked as holes for none), counted and flagged in `voids`.
/// Throws InputError (naming the file) for a missing, unreadable, empty or
/// all-nodata raster.
Heightfield load_dem(const TerrainOptions& o, std::vector<std::string>* warnings = nullptr);

/// Mapbox terrain-RGB: -10000 + (R*65536 + G*256 + B) * 0.1 metres.
inline double decode_terrain_rgb(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return -10000.0 + (r * 65536.0 + g * 256.0 + b) * 0.1;
}
/// Terrarium: R*256 + G + B/256 - 32768 metres.
inline double decode_terrarium(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return r * 256.0 + g + b / 256.0 - 32768.0;
}

}  // namespace terrasprite
