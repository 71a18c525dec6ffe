// SPDX-License-Identifier: MIT
// An inset raster warped into a base's CRS, and the distance from its data
// to its edge: what compositing insets into the base grid and building their
// finer levels share.
#pragma once
#include <vector>

#include "terrasprite/stream/insets.h"

namespace terrasprite::detail {

struct Warped {
  int w = 0, h = 0;
  double gt[6] = {};     ///< GDAL geotransform in the base's CRS
  std::vector<float> v;  ///< w x h heights, NaN where the inset has no data
};

/// The inset warped into `wkt` (bilinear, its own resolution), NaN where it
/// has no data. Throws InputError naming the inset.
Warped warp(const InsetSpec& s, const std::string& wkt);

/// Distance (pixels, chamfer 1 / sqrt 2) from each pixel with data to the
/// nearest pixel without (outside the raster counts as without); 1 at the
/// outermost pixels with data, 0 on pixels without.
std::vector<float> distance_to_void(const std::vector<float>& v, int w, int h);

/// Composites one warped inset into `hf`, whose sample (i, j) lies at
/// (g.x0 + i g.dx, g.y0 - j g.dy): see composite_insets (the blend counts
/// samples of `hf`). `weights` (optional, hf's size) takes each sample's
/// highest weight so far.
InsetResult composite_warped(Heightfield& hf, const GridGeo& g, const InsetSpec& s, const Warped& r,
                             std::vector<float>* weights);

}  // namespace terrasprite::detail
