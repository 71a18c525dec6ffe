// SPDX-License-Identifier: MIT
// A terrain ready to render: heights plus the drape texture over them, and the
// options that build one from files or from the synthetic generator.
#pragma once
#include <array>
#include <optional>
#include <string>

#include "terrasprite/heightfield.h"
#include "terrasprite/image.h"

namespace terrasprite {

/// Heights plus an RGBA drape texture. The texture is mapped over the height
/// samples' extent: terrain coordinates s = i / (width - 1) (west to east) and
/// t = j / (height - 1) (north to south) map to texture coordinates
///   u = tex_rect[0] + s * tex_rect[2],  v = tex_rect[1] + t * tex_rect[3]
/// with v = 0 at the texture's top row. tex_rect is {0, 0, 1, 1} unless both
/// files are georeferenced and cover different areas.
struct Terrain {
  Heightfield heights;
  Image texture;
  std::array<double, 4> tex_rect = {0, 0, 1, 1};
  std::string texture_name = "derived";
};

/// How heights are encoded in an 8-bit RGB PNG.
enum class HeightEncoding { kAuto, kTerrainRgb, kTerrarium };

/// Options of every command that loads a terrain (the CLI's common options).
struct TerrainOptions {
  std::string dem;                ///< height file; empty = synthetic terrain
  bool dem_given = false;         ///< `dem` came from the user: empty is then an error
  std::string texture;            ///< file, "checker", "derived" or empty (= derived)
  double z_scale = 1.0;           ///< multiplies raw samples (after the band's own scale/offset)
  std::optional<double> spacing;  ///< metres between samples; overrides the file's
  std::optional<double> nodata;   ///< nodata value for files that do not tag one
  HeightEncoding encoding = HeightEncoding::kAuto;
  double exaggeration = 1.0;  ///< display scale of heights
  int resample = 0;           ///< 0 = keep; else resample to N x N samples (N >= 2)
  unsigned seed = 1;          ///< synthetic terrain seed
  int synthetic_size = 513;   ///< synthetic terrain samples per side, 2 .. 8193
  int erosion_passes = 2;     ///< synthetic terrain erosion passes, 0 .. 100
};

/// Loads (or synthesises) heights, applies resampling and exaggeration, and
/// builds the drape texture. Throws InputError naming the input on bad data
/// or options: heights that are not finite or beyond 1e7 m after every scale,
/// spacings outside 1e-6 .. 1e6 m. Warnings (e.g. an untagged nodata sentinel) go to `warnings`.
Terrain load_terrain(const TerrainOptions& options, std::vector<std::string>* warnings = nullptr);

}  // namespace terrasprite
