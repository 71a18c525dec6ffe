// SPDX-License-Identifier: MIT
// A terrain ready to render: heights plus the drape texture over them, and the
// options that build one from files or from the synthetic generator.
#pragma once
#include <array>
#include <optional>
#include <string>

#include "terrasprite/common/image.h"
#include "terrasprite/terrain/heightfield.h"

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
  NodataFill fill = NodataFill::kAmle;  ///< how nodata cells are filled
  bool show_voids = false;              ///< tint the drape where the source had nodata (kVoidTint)
  HeightEncoding encoding = HeightEncoding::kAuto;
  double exaggeration = 1.0;  ///< display scale of heights
  int resample = 0;           ///< 0 = keep; else resample to N x N samples (N >= 2)
  unsigned seed = 1;          ///< synthetic terrain seed
  int synthetic_size = 513;   ///< synthetic terrain samples per side, 2 .. 8193
  int erosion_passes = 2;     ///< synthetic terrain erosion passes, 0 .. 100
};

/// Bounds on what a terrain may be, wherever it comes from (a DEM, a tile set,
/// a COG). Heights: beyond 10,000 km from sea level is an encoding or unit
/// mistake; spacing: a micrometre to 1,000 km per sample.
inline constexpr double kMaxAbsHeightM = 1e7;
inline constexpr double kMinSpacingM = 1e-6, kMaxSpacingM = 1e6;

/// Throws InputError naming `name` unless both sample spacings lie within
/// kMinSpacingM .. kMaxSpacingM (NaN and infinities refused).
void check_spacing(const std::string& name, double spacing_x, double spacing_y);

/// Throws InputError naming `name` unless lowest <= highest and both are
/// finite heights within kMaxAbsHeightM; `hint` ends the message when given.
void check_height_range(const std::string& name, double lowest, double highest,
                        const std::string& hint = {});

/// The --show-voids tint: blended half over the drape where cells were nodata.
constexpr std::array<std::uint8_t, 3> kVoidTint = {255, 0, 255};

/// Loads (or synthesises) heights, applies resampling and exaggeration, and
/// builds the drape texture. Throws InputError naming the input on bad data
/// or options: heights that are not finite or beyond 1e7 m after every scale,
/// spacings outside 1e-6 .. 1e6 m. Warnings (e.g. an untagged nodata sentinel) go to `warnings`.
Terrain load_terrain(const TerrainOptions& options, std::vector<std::string>* warnings = nullptr);

/// A terrain whose final grid (after --resample and --exaggeration) is too
/// large to hold (the tile writer's strip-wise path): the source grid in
/// memory, each final sample computed on demand exactly as load_terrain
/// computes it (bilinear from the source, then exaggerated), and the drape
/// texture load_terrain would build for the final grid.
struct LargeTerrain {
  Heightfield source;                       ///< before --resample and --exaggeration
  int width = 0, height = 0;                ///< final samples (>= 2 each)
  double spacing_x = 1.0, spacing_y = 1.0;  ///< final metres between samples
  bool resampled = false;  ///< --resample was given (the source's georeferencing no longer fits)
  double exaggeration = 1.0;
  float min_height = 0, max_height = 0;  ///< over the final grid, metres
  Image texture;
  std::array<double, 4> tex_rect = {0, 0, 1, 1};  ///< as Terrain's
  std::string texture_name = "derived";

  /// Final sample (i, j), metres: 0 <= i < width, 0 <= j < height.
  float at(int i, int j) const;
  /// Row j of the final grid into `out` (width floats). Thread-safe.
  void row(int j, float* out) const;
  /// The final grid through its bilinear sampler (views *this).
  HeightSampler sampler() const;
};

/// Largest final grid side load_large_terrain accepts for --resample.
constexpr int kMaxLargeResample = 65537;

/// load_terrain without holding the final grid: the same checks and errors,
/// but --resample may be up to kMaxLargeResample. One pass over the final grid
/// (computed, not stored) finds its height range and checks its heights.
LargeTerrain load_large_terrain(const TerrainOptions& options,
                                std::vector<std::string>* warnings = nullptr);

}  // namespace terrasprite
