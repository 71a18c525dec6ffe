// SPDX-License-Identifier: MIT
// Shared fixtures of the stream tests.
#pragma once
#include <cpl_conv.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <string>

#include "terrasprite/stream/streaming_tiles.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite::stream_test {

/// The WKT of EPSG code `epsg` (e.g. 32611, UTM 11N).
inline std::string utm_wkt(int epsg) {
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  EXPECT_EQ(OSRImportFromEPSG(srs, epsg), OGRERR_NONE);
  char* w = nullptr;
  OSRExportToWkt(srs, &w);
  std::string s = w;
  CPLFree(w);
  OSRDestroySpatialReference(srs);
  return s;
}

/// Draws `c` through `streamed` until a frame reads nothing coarser than it
/// wanted (at most 20 draws); returns the last frame's stats.
inline StreamFrameStats draw_until_resident(VoxelRenderer& streamed, StreamingTiles& s,
                                            const Camera& c) {
  StreamFrameStats st = s.update(c);
  for (int k = 0; k < 20; ++k) {
    streamed.draw(c);
    s.settle();
    st = s.update(c);
    if (st.degraded_samples == 0) break;
  }
  return st;
}

}  // namespace terrasprite::stream_test
