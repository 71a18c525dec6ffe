// SPDX-License-Identifier: MIT
// Nodata filling through GDAL's GDALFillNodata (inverse distance weighting)
// on an in-memory dataset.
#include <fmt/format.h>
#include <gdal.h>
#include <gdal_alg.h>

#include <algorithm>
#include <vector>

#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/nodata_fill.h"

namespace terrasprite {
namespace {

constexpr int kSmoothingPasses = 2;

// A MEM dataset of `bands` bands of `type`, closed on destruction.
struct MemRaster {
  GDALDatasetH h = nullptr;
  MemRaster(int w, int hgt, GDALDataType type) {
    GDALDriverH mem = GDALGetDriverByName("MEM");
    if (mem) h = GDALCreate(mem, "", w, hgt, 1, type, nullptr);
  }
  ~MemRaster() {
    if (h) GDALClose(h);
  }
  GDALRasterBandH band() const { return GDALGetRasterBand(h, 1); }
};

}  // namespace

long long fill_nodata_gdal(std::span<float> heights, std::span<std::uint8_t> valid, int width,
                           int height) {
  long long voids = std::count(valid.begin(), valid.end(), std::uint8_t{0});
  if (voids == 0) return 0;
  if (voids == static_cast<long long>(valid.size())) throw InputError("all cells are nodata");
  detail::ensure_gdal();
  detail::GdalErrorCapture capture;
  MemRaster data(width, height, GDT_Float32), mask(width, height, GDT_Byte);
  if (!data.h || !mask.h)
    throw InputError(fmt::format("GDALFillNodata: no in-memory raster ({})", capture.last()));
  bool ok = GDALRasterIO(data.band(), GF_Write, 0, 0, width, height, heights.data(), width, height,
                         GDT_Float32, 0, 0) == CE_None &&
            GDALRasterIO(mask.band(), GF_Write, 0, 0, width, height, valid.data(), width, height,
                         GDT_Byte, 0, 0) == CE_None;
  const double reach = std::max(width, height);
  ok = ok && GDALFillNodata(data.band(), mask.band(), reach, 0, kSmoothingPasses, nullptr, nullptr,
                            nullptr) == CE_None;
  std::vector<float> filled(heights.size());
  ok = ok && GDALRasterIO(data.band(), GF_Read, 0, 0, width, height, filled.data(), width, height,
                          GDT_Float32, 0, 0) == CE_None;
  if (!ok) throw InputError(fmt::format("GDALFillNodata failed ({})", capture.last()));
  std::copy(filled.begin(), filled.end(), heights.begin());
  std::fill(valid.begin(), valid.end(), std::uint8_t{1});
  return voids;
}

}  // namespace terrasprite
