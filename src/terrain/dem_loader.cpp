// SPDX-License-Identifier: MIT
// Height rasters through GDAL: geotransform to metres, band scale/offset,
// nodata (tagged, given, or detected sentinels), terrain-RGB/Terrarium PNGs.
#include "terrasprite/terrain/dem_loader.h"

#include <fmt/format.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"
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

namespace {

// An open height raster, checked for size, with its reads' errors naming it.
struct HeightRaster {
  const std::string& path;
  detail::GdalErrorCapture& capture;
  Dataset ds;
  int w = 0, h = 0, bands = 0;
  std::size_t n = 0;  // samples

  // Band `band` (1-based) whole as `t` into `dst`.
  void read(int band, GDALDataType t, void* dst) const {
    if (GDALRasterIO(GDALGetRasterBand(ds.h, band), GF_Read, 0, 0, w, h, dst, w, h, t, 0, 0) !=
        CE_None)
      throw InputError(fmt::format("{}: read failed ({})", path, capture.last()));
  }
};

// Opens `r.path` and checks that it is a raster of a size we can hold.
void open_height_raster(HeightRaster& r) {
  const std::string& path = r.path;
  std::error_code ec;
  // GDAL's virtual files (/vsimem/, /vsizip/...) are not on the filesystem.
  const bool gdal_virtual = path.rfind("/vsi", 0) == 0;
  if (!gdal_virtual && !std::filesystem::exists(path, ec))
    throw InputError(fmt::format("{}: no such file", path));
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{}: is a directory, not a height raster", path));
  r.ds.h = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!r.ds.h) {
    std::string why = r.capture.last().empty() ? "unsupported or corrupt raster" : r.capture.last();
    std::replace(why.begin(), why.end(), '\n', ' ');
    throw InputError(fmt::format("{}: not a readable height raster ({})", path, why));
  }
  const int w = GDALGetRasterXSize(r.ds.h), h = GDALGetRasterYSize(r.ds.h),
            bands = GDALGetRasterCount(r.ds.h);
  if (w <= 0 || h <= 0 || bands <= 0) throw InputError(fmt::format("{}: raster is empty", path));
  if (w < 2 || h < 2)
    throw InputError(
        fmt::format("{}: raster is {}x{}; at least 2x2 samples are needed", path, w, h));
  if (static_cast<long long>(w) * h > 16385LL * 16385LL)
    throw InputError(fmt::format(
        "{}: raster is {}x{}; more than 16385x16385 samples is not supported yet", path, w, h));
  r.w = w;
  r.h = h;
  r.bands = bands;
  r.n = static_cast<std::size_t>(w) * h;
}

// The encoding to read `r` with: `asked`, checked against the raster's bands.
HeightEncoding checked_encoding(const HeightRaster& r, HeightEncoding asked) {
  const bool bytes = GDALGetRasterDataType(GDALGetRasterBand(r.ds.h, 1)) == GDT_Byte;
  if (asked == HeightEncoding::kAuto && bytes && r.bands >= 3)
    throw InputError(
        fmt::format("{}: an 8-bit colour raster; give --encoding terrain-rgb or terrarium to read "
                    "it as heights",
                    r.path));
  if (asked != HeightEncoding::kAuto && (!bytes || r.bands < 3))
    throw InputError(fmt::format("{}: --encoding needs an 8-bit RGB raster", r.path));
  return asked;
}

// Heights decoded from an RGB(A) raster; alpha 0 marks nodata.
void decode_rgb_heights(const HeightRaster& r, HeightEncoding enc, std::vector<double>& raw,
                        std::vector<std::uint8_t>& valid, std::vector<std::string>* warnings) {
  const std::size_t n = r.n;
  std::vector<std::uint8_t> rgb[3];
  for (int c = 0; c < 3; ++c) {
    rgb[c].resize(n);
    r.read(c + 1, GDT_Byte, rgb[c].data());
  }
  std::vector<std::uint8_t> alpha;
  if (r.bands >= 4) {
    alpha.resize(n);
    r.read(4, GDT_Byte, alpha.data());
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
        r.path, outside, n, enc == HeightEncoding::kTerrainRgb ? "terrain-RGB" : "Terrarium"));
}

// Heights of band 1 (its scale and offset applied); nodata as tagged or as
// `given`, with a warning for untagged typical sentinels.
void read_band_heights(const HeightRaster& r, const std::optional<double>& given,
                       std::vector<double>& raw, std::vector<std::uint8_t>& valid,
                       std::vector<std::string>* warnings) {
  const std::size_t n = r.n;
  GDALRasterBandH b1 = GDALGetRasterBand(r.ds.h, 1);
  r.read(1, GDT_Float64, raw.data());
  int has_nodata = 0;
  double nodata = GDALGetRasterNoDataValue(b1, &has_nodata);
  if (given) {
    has_nodata = 1;
    nodata = *given;
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
                      r.path, sentinel_count[s], sentinels[s], sentinels[s]));
  int ok = 0;
  double scale = GDALGetRasterScale(b1, &ok);
  if (!ok) scale = 1.0;
  double offset = GDALGetRasterOffset(b1, &ok);
  if (!ok) offset = 0.0;
  for (std::size_t p = 0; p < n; ++p) raw[p] = raw[p] * scale + offset;
}

// Sample spacing from the georeferencing (or `o.spacing`, or 30 m with a warning).
void set_spacing(const HeightRaster& r, const TerrainOptions& o, bool has_gt, const double gt[6],
                 Heightfield& hf, std::vector<std::string>* warnings) {
  GeoTransform geo;
  double sx = 30.0, sy = 30.0;
  if (has_gt && detail::spacing_from_geo(r.ds.h, gt, r.w, r.h, sx, sy, geo)) {
    hf.geo = geo;
    hf.geo_width = r.w;
    hf.geo_height = r.h;
  }
  if (o.spacing) {
    sx = sy = *o.spacing;
  } else if (!hf.geo && warnings) {
    warnings->push_back(
        fmt::format("{}: no georeferencing; assuming 30 m spacing (use --spacing)", r.path));
  }
  if (!(sx > 0) || !(sy > 0) || !std::isfinite(sx) || !std::isfinite(sy))
    throw InputError(fmt::format("{}: sample spacing {}x{} m is not positive", r.path, sx, sy));
  hf.spacing_x = sx;
  hf.spacing_y = sy;
}

}  // namespace

Heightfield load_dem(const TerrainOptions& o, std::vector<std::string>* warnings) {
  const std::string& path = o.dem;
  detail::GdalErrorCapture capture;
  HeightRaster r{path, capture, {}};
  open_height_raster(r);
  const HeightEncoding enc = checked_encoding(r, o.encoding);

  std::vector<double> raw(r.n);
  std::vector<std::uint8_t> valid(r.n, 1);
  if (enc != HeightEncoding::kAuto)
    decode_rgb_heights(r, enc, raw, valid, warnings);
  else
    read_band_heights(r, o.nodata, raw, valid, warnings);

  double gt[6] = {0, 1, 0, 0, 0, 1};
  const bool has_gt = geotransform_of(r.ds.h, gt);
  if (has_gt) orient_north_up(path, r.w, r.h, gt, raw, valid);

  Heightfield hf;
  hf.width = r.w;
  hf.height = r.h;
  hf.name = std::filesystem::path(path).filename().string();
  hf.heights.resize(r.n);
  for (std::size_t p = 0; p < r.n; ++p) hf.heights[p] = valid[p] ? float(raw[p] * o.z_scale) : 0.f;
  if (std::find(valid.begin(), valid.end(), std::uint8_t{0}) != valid.end()) {
    hf.voids.resize(r.n);
    for (std::size_t p = 0; p < r.n; ++p) hf.voids[p] = valid[p] ? 0 : 1;
  }
  hf.fill_method = o.fill;
  try {
    hf.nodata_count = o.fill == NodataFill::kGdal ? fill_nodata_gdal(hf.heights, valid, r.w, r.h)
                                                  : fill_nodata(hf.heights, valid, r.w, r.h);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", path, e.what()));
  }
  set_spacing(r, o, has_gt, gt, hf, warnings);
  return hf;
}

}  // namespace terrasprite
