// SPDX-License-Identifier: MIT
// High-resolution insets (Cohen-Or et al.'s target areas) over a base
// terrain: each inset raster is reprojected by GDAL into the base's CRS and
// its samples replace the base's where it has data, blended over a few grid
// samples at its border so the surface stays continuous.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// `FILE[:blend=N]`: an inset raster and its border blend in grid samples.
struct InsetSpec {
  std::string path;
  int blend = 4;  ///< samples of the output grid over which the inset fades in; 0: a hard edge
};

/// Parses `FILE[:blend=N]` (N 0..1024). Throws InputError naming the argument.
InsetSpec parse_inset(const std::string& arg);

/// Where the samples of a grid lie in a CRS: sample (i, j) at
/// (x0 + i dx, y0 - j dy), north up, `wkt` the CRS.
struct GridGeo {
  double x0 = 0, y0 = 0, dx = 1, dy = 1;
  std::string wkt;
};

/// The grid of `hf` in its source's CRS: its corner samples are the source
/// raster's corner pixel centres (as resample_heightfield keeps them), so
/// `source_w` x `source_h` is the raster's size before any resampling.
/// Throws InputError when `hf` carries no georeferencing.
GridGeo grid_geo(const Heightfield& hf, int source_w, int source_h);

/// Width and height of the raster at `path` (throws InputError naming it).
std::pair<int, int> raster_size(const std::string& path);

/// What one inset changed.
struct InsetResult {
  std::string path;
  int blend = 0;
  long long samples_replaced = 0;  ///< grid samples with a weight > 0
  long long samples_full = 0;      ///< of those, weight 1 (the inset's own value)
  double spacing_m[2] = {0, 0};    ///< the inset's pixel size after reprojection, CRS units
};

/// Composites `insets` into `hf` in order (a later inset over an earlier).
/// Each is warped by GDAL (bilinear) into `grid.wkt` at its own resolution,
/// held in memory (the warped inset only, never the base twice), and sampled
/// bilinearly at every grid sample it covers where all four neighbours have
/// data; the weight is the distance to the inset's data edge (in grid
/// samples, 0 at the outermost pixel centres) over `blend`, capped at 1:
/// h = base + w (inset - base). Throws InputError naming an inset GDAL
/// cannot read or warp, or one that covers no sample of the grid.
std::vector<InsetResult> composite_insets(Heightfield& hf, const GridGeo& grid,
                                          const std::vector<InsetSpec>& insets);

}  // namespace terrasprite
