// SPDX-License-Identifier: MIT
// GDAL set-up and error capture: GDAL's own messages become part of our
// one-line InputError instead of being printed.
#pragma once
#include <string>

typedef void* GDALDatasetH;

namespace terrasprite {
struct GeoTransform;
}

namespace terrasprite::detail {

/// Registers GDAL's drivers once (thread-safe).
void ensure_gdal();

/// While alive, GDAL errors on this thread are collected, not printed.
class GdalErrorCapture {
 public:
  GdalErrorCapture();
  ~GdalErrorCapture();
  GdalErrorCapture(const GdalErrorCapture&) = delete;
  GdalErrorCapture& operator=(const GdalErrorCapture&) = delete;
  /// The last error GDAL reported, or "" when none.
  const std::string& last() const { return last_; }

 private:
  std::string last_;
};

/// Ground spacing in metres (sx, sy) of a north-up raster `w` x `h` with
/// transform `gt` (geographic CRSs at the raster's central latitude); `geo`
/// gets the transform and WKT. False when the raster carries no usable
/// georeferencing.
bool spacing_from_geo(GDALDatasetH ds, const double gt[6], int w, int h, double& sx, double& sy,
                      GeoTransform& geo);

}  // namespace terrasprite::detail
