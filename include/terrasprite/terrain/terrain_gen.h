// SPDX-License-Identifier: MIT
// Building blocks of terrain loading: DEM readers, nodata filling, the
// synthetic generator, resampling and generated drape textures.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "terrasprite/terrain/heightfield.h"
#include "terrasprite/common/image.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

/// Reads a height raster: any GDAL raster (GeoTIFF, SRTM .hgt, DTED, ASCII
/// grid, VRT, 16-bit PNG, ...), or an 8-bit RGB PNG in terrain-RGB/Terrarium
/// encoding. Uses these fields of `o`: dem, z_scale, spacing, nodata, encoding.
/// Spacing comes from the geotransform (projected units converted to metres;
/// geographic degrees converted at the raster's centre latitude) unless
/// `o.spacing` is set; a raster without georeferencing gets 30 m and a warning.
/// Nodata cells are filled from their neighbours and counted.
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

/// Fills cells whose `valid` flag is 0 with the harmonic (Laplace) surface
/// whose boundary values are the valid cells: smooth, no steps, no new peaks
/// or pits, slopes no steeper than around the void. Sets every flag to 1.
/// Returns the number of cells filled.
/// `heights` and `valid` hold width*height entries. Throws InputError
/// ("all cells are nodata") when no cell is valid.
long long fill_nodata(std::span<float> heights, std::span<std::uint8_t> valid, int width,
                      int height);

/// Seeded, deterministic mountains: fBm plus ridged noise, a few thermal
/// erosion passes, heights normalised to [0, relief_m]. size >= 2.
struct SynthOptions {
  int size = 513;  ///< samples per side
  double spacing_m = 30.0;
  double relief_m = 2000.0;
  unsigned seed = 1;
  int erosion_passes = 2;
};
Heightfield synthesize_terrain(const SynthOptions& o);

/// Bilinear resampling to width x height samples over the same extent.
Heightfield resample_heightfield(const Heightfield& h, int width, int height);

/// Elevation colour ramp times hillshade, sampled at texel centres over the
/// height samples' extent (Terrain's mapping). width, height >= 1.
Image derived_texture(const Heightfield& h, int width, int height);
Image derived_texture(const HeightSampler& h, int width, int height);

/// The paper's red/green checkerboard (its Fig. 13): `squares` per side.
Image checker_texture(int squares, int size_px);

}  // namespace terrasprite
