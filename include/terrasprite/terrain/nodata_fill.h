// SPDX-License-Identifier: MIT
// Filling the voids (nodata cells) of a height raster.
#pragma once
#include <cstdint>
#include <span>

namespace terrasprite {

/// Fills cells whose `valid` flag is 0 with the absolutely minimizing
/// Lipschitz extension (AMLE) of the valid cells around them: of all
/// surfaces taking the rim's values, the one whose steepest slope is least,
/// so no fill is steeper than the rim demands (no cliffs, no new peaks or
/// pits). Sets every flag to 1 and returns the number of cells filled.
/// `heights` and `valid` hold width*height entries (row-major). Throws
/// InputError ("all cells are nodata") when no cell is valid.
long long fill_nodata(std::span<float> heights, std::span<std::uint8_t> valid, int width,
                      int height);

/// fill_nodata by GDAL's GDALFillNodata instead: inverse-distance weighting
/// of the valid cells found along rays from each void cell (searching the
/// whole raster), then smoothed by 2 passes of a 3x3 filter. Same contract
/// and result count as fill_nodata.
long long fill_nodata_gdal(std::span<float> heights, std::span<std::uint8_t> valid, int width,
                           int height);

}  // namespace terrasprite
