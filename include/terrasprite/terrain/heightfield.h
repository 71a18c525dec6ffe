// SPDX-License-Identifier: MIT
// A regular grid of terrain heights.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/common/image.h"

namespace terrasprite {

/// How a loader fills nodata cells (voids): AMLE (fill_nodata, the default),
/// GDAL's inverse-distance GDALFillNodata, or none (the cells stay marked as
/// holes; their heights are AMLE's so the grid stays whole).
enum class NodataFill { kAmle, kGdal, kNone };
const char* to_string(NodataFill f);

/// Heights in metres on a regular grid. Row-major; row 0 is the northern edge,
/// column 0 the western edge. Sample (i, j) (column i, row j) lies at world
///   x = (i - (width - 1) / 2) * spacing_x      (east)
///   y = ((height - 1) / 2 - j) * spacing_y     (north)
/// so the grid is centred on the origin. All heights are valid (nodata cells
/// have been filled by the loader and counted in `nodata_count`).
struct Heightfield {
  int width = 0;                               ///< samples along x (>= 1)
  int height = 0;                              ///< samples along y (>= 1)
  double spacing_x = 1.0;                      ///< metres between samples along x (> 0)
  double spacing_y = 1.0;                      ///< metres between samples along y (> 0)
  std::vector<float> heights;                  ///< width * height values, metres
  long long nodata_count = 0;                  ///< cells that were nodata in the source (filled)
  NodataFill fill_method = NodataFill::kAmle;  ///< how they were filled
  /// 1 where a cell was nodata in the source, per sample (row-major, this
  /// grid's size); empty when no cell was.
  std::vector<std::uint8_t> voids;
  std::optional<GeoTransform> geo;  ///< source georeferencing, when known
  /// Samples of the grid `geo` describes (the source's: a resampled grid
  /// keeps its corners on the source's corner samples).
  int geo_width = 0, geo_height = 0;
  std::optional<std::pair<int, int>> resampled_to;    ///< set when the grid was resampled
  std::optional<std::pair<int, int>> resampled_from;  ///< the source's samples, when resampled
  std::string name = "unnamed";

  float at(int i, int j) const { return heights[static_cast<std::size_t>(j) * width + i]; }
  float& at(int i, int j) { return heights[static_cast<std::size_t>(j) * width + i]; }
  double extent_x() const { return (width - 1) * spacing_x; }
  double extent_y() const { return (height - 1) * spacing_y; }
  /// Larger side of the extent, metres (the paper path's unit E).
  double extent() const { return extent_x() > extent_y() ? extent_x() : extent_y(); }
  double world_x(double i) const { return (i - (width - 1) * 0.5) * spacing_x; }
  double world_y(double j) const { return ((height - 1) * 0.5 - j) * spacing_y; }
  /// Bilinear height at world (x, y) in metres, clamped to the grid's border.
  float sample(double x, double y) const;
  float min_height() const;
  float max_height() const;
};

/// A height field seen through its bilinear sampler: one held in memory
/// (height_sampler) or one computed on demand, too large to hold (LargeTerrain).
struct HeightSampler {
  std::function<float(double x, double y)> sample;  ///< as Heightfield::sample, metres
  int width = 0, height = 0;                        ///< samples
  double spacing_x = 1.0, spacing_y = 1.0;          ///< metres between samples
  float min_height = 0, max_height = 0;             ///< over every sample, metres
  double extent_x() const { return (width - 1) * spacing_x; }
  double extent_y() const { return (height - 1) * spacing_y; }
};
/// A sampler viewing `h` (which must outlive it).
HeightSampler height_sampler(const Heightfield& h);

}  // namespace terrasprite
