// SPDX-License-Identifier: MIT
// WGS 84 longitude/latitude to terrain world metres through GDAL/OGR.
#include "terrasprite/terrain/geo_frame.h"

#include <fmt/format.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>

#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"

namespace terrasprite {

struct GeoFrame::Impl {
  OGRSpatialReference wgs84, raster;
  std::unique_ptr<OGRCoordinateTransformation> to_raster, to_wgs84;
  double gt[6] = {0, 1, 0, 0, 0, 1};
  int geo_w = 0, geo_h = 0;           // samples `gt` describes
  double extent_x = 0, extent_y = 0;  // world metres
};

bool has_crs(const Heightfield& h) {
  return h.geo && !h.geo->wkt.empty();
}

GeoFrame::GeoFrame(const Heightfield& h, const std::string& what)
    : impl_(std::make_unique<Impl>()) {
  if (!has_crs(h))
    throw InputError(fmt::format(
        "{}: {} has no coordinate reference system, so geographic places cannot be put on it "
        "(give positions in metres from its centre)",
        what, h.name));
  detail::ensure_gdal();
  detail::GdalErrorCapture capture;
  Impl& m = *impl_;
  m.wgs84.SetWellKnownGeogCS("WGS84");
  m.wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (m.raster.importFromWkt(h.geo->wkt.c_str()) != OGRERR_NONE)
    throw InputError(
        fmt::format("{}: the CRS of {} cannot be read ({})", what, h.name, capture.last()));
  m.raster.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  m.to_raster.reset(OGRCreateCoordinateTransformation(&m.wgs84, &m.raster));
  m.to_wgs84.reset(OGRCreateCoordinateTransformation(&m.raster, &m.wgs84));
  if (!m.to_raster || !m.to_wgs84)
    throw InputError(fmt::format("{}: no transformation from WGS 84 to the CRS of {} ({})", what,
                                 h.name, capture.last()));
  std::copy(h.geo->gt, h.geo->gt + 6, m.gt);
  m.geo_w = h.geo_width > 1 ? h.geo_width : h.width;
  m.geo_h = h.geo_height > 1 ? h.geo_height : h.height;
  m.extent_x = h.extent_x();
  m.extent_y = h.extent_y();
}

GeoFrame::~GeoFrame() = default;
GeoFrame::GeoFrame(GeoFrame&&) noexcept = default;
GeoFrame& GeoFrame::operator=(GeoFrame&&) noexcept = default;

WorldXY GeoFrame::world_of(double lon, double lat, GeoMargin margin,
                           const std::string& what) const {
  if (!std::isfinite(lon) || !std::isfinite(lat))
    throw InputError(
        fmt::format("{} {},{}: longitude and latitude must be finite", what, lon, lat));
  if (lat < -90 || lat > 90)
    throw InputError(fmt::format(
        "{} {},{}: latitude must be within -90 .. 90 degrees (the order is longitude, latitude)",
        what, lon, lat));
  if (lon < -180 || lon > 360)
    throw InputError(
        fmt::format("{} {},{}: longitude must be within -180 .. 360 degrees", what, lon, lat));
  const Impl& m = *impl_;
  double X = lon, Y = lat;
  if (!m.to_raster->Transform(1, &X, &Y))
    throw InputError(
        fmt::format("{} {},{}: outside the area the terrain's CRS can represent", what, lon, lat));
  // Fractions of the grid from its first to its last sample centre.
  const double fx = ((X - m.gt[0]) / m.gt[1] - 0.5) / (m.geo_w - 1);
  const double fy = ((Y - m.gt[3]) / m.gt[5] - 0.5) / (m.geo_h - 1);
  const double slack = margin == GeoMargin::kOnTerrain ? 1e-9 : 1.0;
  if (!(fx >= -slack && fx <= 1 + slack && fy >= -slack && fy <= 1 + slack))
    throw InputError(
        fmt::format("{} {},{}: {} the terrain (its corners are {})", what, lon, lat,
                    margin == GeoMargin::kOnTerrain ? "not on" : "more than one extent away from",
                    footprint_text()));
  return {(fx - 0.5) * m.extent_x, (0.5 - fy) * m.extent_y};
}

std::pair<double, double> GeoFrame::lonlat_of(WorldXY p) const {
  const Impl& m = *impl_;
  const double fx = p.x / m.extent_x + 0.5, fy = 0.5 - p.y / m.extent_y;
  double X = m.gt[0] + (fx * (m.geo_w - 1) + 0.5) * m.gt[1];
  double Y = m.gt[3] + (fy * (m.geo_h - 1) + 0.5) * m.gt[5];
  if (!m.to_wgs84->Transform(1, &X, &Y)) return {NAN, NAN};
  return {X, Y};
}

std::string GeoFrame::footprint_text() const {
  const auto [w, n] = lonlat_of({-0.5 * impl_->extent_x, 0.5 * impl_->extent_y});
  const auto [e, s] = lonlat_of({0.5 * impl_->extent_x, -0.5 * impl_->extent_y});
  return fmt::format("{:.5f},{:.5f} (north-west) and {:.5f},{:.5f} (south-east)", w, n, e, s);
}

std::string GeoFrame::crs_name() const {
  const OGRSpatialReference& r = impl_->raster;
  const char* name = r.GetName();
  const char* authority = r.GetAuthorityName(nullptr);
  const char* code = r.GetAuthorityCode(nullptr);
  const std::string named = name ? name : "unnamed CRS";
  if (!authority || !code) return named;
  return fmt::format("{}:{} ({})", authority, code, named);
}

std::array<double, 4> GeoFrame::lonlat_box() const {
  std::array<double, 4> box = {INFINITY, INFINITY, -INFINITY, -INFINITY};
  const double hx = 0.5 * impl_->extent_x, hy = 0.5 * impl_->extent_y;
  for (double fx : {-1.0, 0.0, 1.0})
    for (double fy : {-1.0, 0.0, 1.0}) {
      const auto [lon, lat] = lonlat_of({fx * hx, fy * hy});
      box = {std::min(box[0], lon), std::min(box[1], lat), std::max(box[2], lon),
             std::max(box[3], lat)};
    }
  return box;
}

}  // namespace terrasprite
