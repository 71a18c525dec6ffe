// SPDX-License-Identifier: MIT
// Height rasters through GDAL: geotransform to metres, band scale/offset,
// nodata (tagged, given, or detected sentinels), terrain-RGB/Terrarium PNGs.
#include <fmt/format.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/dem_loader.h"
#include "terrasprite/terrain/nodata_fill.h"

namespace terrasprite {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Dataset {
  GDALDatasetH h = nullptr;
  ~Dataset() {
    if (h) GDALClose(h);
  }
};

// Metres per degree of latitude and longitude at latitude `lat_deg` (WGS 84
// series expansion), so geographic rasters get true ground spacing.
void metres_per_degree(double lat_deg, double& m_lat, double& m_lon) {
  double p = lat_deg * kPi / 180.0;
  m_lat = 111132.92 - 559.82 * std::cos(2 * p) + 1.175 * std::cos(4 * p) - 0.0023 * std::cos(6 * p);
  m_lon = 111412.84 * std::cos(p) - 93.5 * std::cos(3 * p) + 0.118 * std::cos(5 * p);
}

// The raster's geotransform, or false when it has none.
bool geotransform_of(GDALDatasetH ds, double gt[6]) {
  if (GDALGetGeoTransform(ds, gt) != CE_None) return false;
  // Some drivers report the identity for "none": pixel units, rows downwards.
  return !(gt[0] == 0 && gt[1] == 1 && gt[2] == 0 && gt[3] == 0 && gt[4] == 0 && gt[5] == 1);
}

// Mirrors samples so that row 0 is north and column 0 west whatever the
// geotransform's signs (a south-up raster has a positive pixel height, a
// mirrored one a negative pixel width), and rewrites `gt` to describe the
// result. Rotated rasters are refused: a grid at an angle is not our frame.
void orient_north_up(const std::string& path, int w, int h, double gt[6], std::vector<double>& raw,
                     std::vector<std::uint8_t>& valid) {
  if (gt[2] != 0 || gt[4] != 0)
    throw InputError(fmt::format(
        "{}: the geotransform is rotated (terms {:g}, {:g}); warp it north-up first, e.g. "
        "gdalwarp {} north_up.tif",
        path, gt[2], gt[4], path));
  auto at = [w](int i, int j) { return std::size_t(j) * w + i; };
  if (gt[1] < 0) {
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w / 2; ++i) {
        std::swap(raw[at(i, j)], raw[at(w - 1 - i, j)]);
        std::swap(valid[at(i, j)], valid[at(w - 1 - i, j)]);
      }
    gt[0] += w * gt[1];
    gt[1] = -gt[1];
  }
  if (gt[5] > 0) {
    for (int j = 0; j < h / 2; ++j)
      for (int i = 0; i < w; ++i) {
        std::swap(raw[at(i, j)], raw[at(i, h - 1 - j)]);
        std::swap(valid[at(i, j)], valid[at(i, h - 1 - j)]);
      }
    gt[3] += h * gt[5];
    gt[5] = -gt[5];
  }
}

}  // namespace

namespace detail {

bool spacing_from_geo(GDALDatasetH ds, const double gt[6], int w, int h, double& sx, double& sy,
                      GeoTransform& geo) {
  if (gt[0] == 0 && gt[1] == 1 && gt[2] == 0 && gt[3] == 0 && gt[4] == 0 && gt[5] == 1)
    return false;
  std::copy(gt, gt + 6, geo.gt);
  const char* wkt = GDALGetProjectionRef(ds);
  geo.wkt = wkt ? wkt : "";
  double px = std::hypot(gt[1], gt[4]), py = std::hypot(gt[2], gt[5]);
  if (geo.wkt.empty()) {
    sx = px;  // no CRS: assume the transform is in metres
    sy = py;
    return true;
  }
  OGRSpatialReferenceH srs = OSRNewSpatialReference(geo.wkt.c_str());
  if (srs && OSRIsGeographic(srs)) {
    double lat = gt[3] + (w * 0.5) * gt[4] + (h * 0.5) * gt[5];
    double m_lat, m_lon;
    metres_per_degree(lat, m_lat, m_lon);
    sx = px * m_lon;
    sy = py * m_lat;
  } else {
    double unit = srs ? OSRGetLinearUnits(srs, nullptr) : 1.0;
    sx = px * unit;
    sy = py * unit;
  }
  if (srs) OSRDestroySpatialReference(srs);
  return true;
}

}  // namespace detail

Heightfield load_dem(const TerrainOptions& o, std::vector<std::string>* warnings) {
  const std::string& path = o.dem;
  std::error_code ec;
  // GDAL's virtual files (/vsimem/, /vsizip/...) are not on the filesystem.
  const bool gdal_virtual = path.rfind("/vsi", 0) == 0;
  if (!gdal_virtual && !std::filesystem::exists(path, ec))
    throw InputError(fmt::format("{}: no such file", path));
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{}: is a directory, not a height raster", path));
  detail::GdalErrorCapture capture;
  Dataset ds{GDALOpen(path.c_str(), GA_ReadOnly)};
  if (!ds.h) {
    std::string why = capture.last().empty() ? "unsupported or corrupt raster" : capture.last();
    std::replace(why.begin(), why.end(), '\n', ' ');
    throw InputError(fmt::format("{}: not a readable height raster ({})", path, why));
  }
  const int w = GDALGetRasterXSize(ds.h), h = GDALGetRasterYSize(ds.h),
            bands = GDALGetRasterCount(ds.h);
  if (w <= 0 || h <= 0 || bands <= 0) throw InputError(fmt::format("{}: raster is empty", path));
  if (w < 2 || h < 2)
    throw InputError(
        fmt::format("{}: raster is {}x{}; at least 2x2 samples are needed", path, w, h));
  if (static_cast<long long>(w) * h > 16385LL * 16385LL)
    throw InputError(fmt::format(
        "{}: raster is {}x{}; more than 16385x16385 samples is not supported yet", path, w, h));

  GDALRasterBandH b1 = GDALGetRasterBand(ds.h, 1);
  const bool bytes = GDALGetRasterDataType(b1) == GDT_Byte;
  HeightEncoding enc = o.encoding;
  if (enc == HeightEncoding::kAuto && bytes && bands >= 3)
    throw InputError(
        fmt::format("{}: an 8-bit colour raster; give --encoding terrain-rgb or terrarium to read "
                    "it as heights",
                    path));
  if (enc != HeightEncoding::kAuto && (!bytes || bands < 3))
    throw InputError(fmt::format("{}: --encoding needs an 8-bit RGB raster", path));

  const std::size_t n = static_cast<std::size_t>(w) * h;
  std::vector<double> raw(n);
  std::vector<std::uint8_t> valid(n, 1);
  auto read = [&](GDALRasterBandH band, GDALDataType t, void* dst) {
    if (GDALRasterIO(band, GF_Read, 0, 0, w, h, dst, w, h, t, 0, 0) != CE_None)
      throw InputError(fmt::format("{}: read failed ({})", path, capture.last()));
  };
  if (enc != HeightEncoding::kAuto) {
    std::vector<std::uint8_t> rgb[3];
    for (int c = 0; c < 3; ++c) {
      rgb[c].resize(n);
      read(GDALGetRasterBand(ds.h, c + 1), GDT_Byte, rgb[c].data());
    }
    std::vector<std::uint8_t> alpha;
    if (bands >= 4) {
      alpha.resize(n);
      read(GDALGetRasterBand(ds.h, 4), GDT_Byte, alpha.data());
    }
    long long outside = 0;
    for (std::size_t p = 0; p < n; ++p) {
      raw[p] = enc == HeightEncoding::kTerrainRgb
                   ? decode_terrain_rgb(rgb[0][p], rgb[1][p], rgb[2][p])
                   : decode_terrarium(rgb[0][p], rgb[1][p], rgb[2][p]);
      if (!alpha.empty() && alpha[p] == 0) valid[p] = 0;
      // Earth's surface lies within -11 km (the Mariana Trench) .. +8.8 km.
      outside += valid[p] && (raw[p] < -12000 || raw[p] > 9000);
    }
    if (outside && warnings)
      warnings->push_back(fmt::format(
          "{}: {} of {} decoded heights lie outside -12 km .. +9 km; is this really {}-encoded?",
          path, outside, n, enc == HeightEncoding::kTerrainRgb ? "terrain-RGB" : "Terrarium"));
  } else {
    read(b1, GDT_Float64, raw.data());
    int has_nodata = 0;
    double nodata = GDALGetRasterNoDataValue(b1, &has_nodata);
    if (o.nodata) {
      has_nodata = 1;
      nodata = *o.nodata;
    }
    long long sentinel_count[3] = {0, 0, 0};
    const double sentinels[3] = {-32768, -32767, -9999};
    for (std::size_t p = 0; p < n; ++p) {
      double v = raw[p];
      if (!std::isfinite(v) ||
          (has_nodata && (v == nodata || (std::isnan(nodata) && std::isnan(v))))) {
        valid[p] = 0;
        continue;
      }
      if (!has_nodata)
        for (int s = 0; s < 3; ++s) sentinel_count[s] += v == sentinels[s];
    }
    for (int s = 0; s < 3; ++s)
      if (warnings && sentinel_count[s] * 1000 >= static_cast<long long>(n))  // >= 0.1% of cells
        warnings->push_back(
            fmt::format("{}: {} cells hold {}, a typical nodata sentinel, but the file tags no "
                        "nodata; pass --nodata {} to treat them as holes",
                        path, sentinel_count[s], sentinels[s], sentinels[s]));
    int ok = 0;
    double scale = GDALGetRasterScale(b1, &ok);
    if (!ok) scale = 1.0;
    double offset = GDALGetRasterOffset(b1, &ok);
    if (!ok) offset = 0.0;
    for (std::size_t p = 0; p < n; ++p) raw[p] = raw[p] * scale + offset;
  }

  double gt[6] = {0, 1, 0, 0, 0, 1};
  const bool has_gt = geotransform_of(ds.h, gt);
  if (has_gt) orient_north_up(path, w, h, gt, raw, valid);

  Heightfield hf;
  hf.width = w;
  hf.height = h;
  hf.name = std::filesystem::path(path).filename().string();
  hf.heights.resize(n);
  for (std::size_t p = 0; p < n; ++p) hf.heights[p] = valid[p] ? float(raw[p] * o.z_scale) : 0.f;
  try {
    hf.nodata_count = fill_nodata(hf.heights, valid, w, h);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", path, e.what()));
  }

  GeoTransform geo;
  double sx = 30.0, sy = 30.0;
  if (has_gt && detail::spacing_from_geo(ds.h, gt, w, h, sx, sy, geo)) hf.geo = geo;
  if (o.spacing) {
    sx = sy = *o.spacing;
  } else if (!hf.geo && warnings) {
    warnings->push_back(
        fmt::format("{}: no georeferencing; assuming 30 m spacing (use --spacing)", path));
  }
  if (!(sx > 0) || !(sy > 0) || !std::isfinite(sx) || !std::isfinite(sy))
    throw InputError(fmt::format("{}: sample spacing {}x{} m is not positive", path, sx, sy));
  hf.spacing_x = sx;
  hf.spacing_y = sy;
  return hf;
}

}  // namespace terrasprite
