// SPDX-License-Identifier: MIT
// Drape-texture registration helpers used by load_terrain (internal).
#pragma once
#include <array>
#include <optional>

#include "terrasprite/terrain/heightfield.h"
#include "terrasprite/common/image.h"

namespace terrasprite::detail {

/// Where the height samples' extent lies in a georeferenced texture, as the
/// Terrain::tex_rect {u0, v0, du, dv} (texture units, v down). The heights'
/// corners are transformed into the texture's CRS when the two differ;
/// nullopt when they cannot be related (no CRS, no transformation).
std::optional<std::array<double, 4>> georegistered_rect(const GeoTransform& heights_geo, int hw,
                                                        int hh, const GeoTransform& texture_geo,
                                                        int tw, int th);

/// Fraction (0..1) of the terrain's extent that `rect` places inside the texture.
double covered_fraction(const std::array<double, 4>& rect);

/// Replaces fully transparent texels (an image's nodata) with the derived
/// texture of `heights` at the same place, opaque. Returns how many there were.
long long fill_transparent_texels(Image& texture, const std::array<double, 4>& rect,
                                  const HeightSampler& heights);

}  // namespace terrasprite::detail
