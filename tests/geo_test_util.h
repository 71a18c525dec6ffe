// SPDX-License-Identifier: MIT
// A small terrain with a CRS: what the geographic tests (camera, terrain) place things on.
#pragma once
#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <string>

#include "terrasprite/terrain/heightfield.h"

namespace tstest {

/// 11 x 11 samples `height` m high, 0.1 degree pixels from 138 E, 36 N
/// (WGS 84, EPSG:4326); 1 km spacing.
inline terrasprite::Heightfield geographic_grid(float height, const std::string& name) {
  terrasprite::Heightfield h;
  h.width = h.height = 11;
  h.spacing_x = h.spacing_y = 1000;
  h.heights.assign(121, height);
  h.name = name;
  OGRSpatialReference s;
  s.importFromEPSG(4326);
  char* w = nullptr;
  s.exportToWkt(&w);
  terrasprite::GeoTransform g;
  const double gt[6] = {138.0, 0.1, 0, 36.0, 0, -0.1};
  std::copy(gt, gt + 6, g.gt);
  g.wkt = w;
  CPLFree(w);
  h.geo = g;
  h.geo_width = h.geo_height = 11;
  return h;
}

}  // namespace tstest
