// SPDX-License-Identifier: MIT
#include "terrasprite/stream/insets.h"

#include <fmt/format.h>
#include <gdal.h>
#include <gdal_utils.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "stream/inset_warp.h"
#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace detail {

// Distance (pixels, chamfer 1 / sqrt 2) from each pixel with data to the
// nearest pixel without (outside the raster counts as without); 1 at the
// outermost pixels with data.
std::vector<float> distance_to_void(const std::vector<float>& v, int w, int h) {
  constexpr float kD = 1.41421356f;
  std::vector<float> d(v.size());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      d[std::size_t(j) * w + i] = std::isnan(v[std::size_t(j) * w + i])
                                      ? 0.f
                                      : float(std::min({i + 1, w - i, j + 1, h - j}));
  auto relax = [&](int i, int j, int di, int dj, float c) {
    const int a = i + di, b = j + dj;
    if (a < 0 || b < 0 || a >= w || b >= h) return;
    float& x = d[std::size_t(j) * w + i];
    x = std::min(x, d[std::size_t(b) * w + a] + c);
  };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      relax(i, j, -1, 0, 1.f);
      relax(i, j, 0, -1, 1.f);
      relax(i, j, -1, -1, kD);
      relax(i, j, 1, -1, kD);
    }
  for (int j = h - 1; j >= 0; --j)
    for (int i = w - 1; i >= 0; --i) {
      relax(i, j, 1, 0, 1.f);
      relax(i, j, 0, 1, 1.f);
      relax(i, j, 1, 1, kD);
      relax(i, j, -1, 1, kD);
    }
  return d;
}

// Refuses an inset GDAL would place by guesswork: without a geotransform or
// a CRS it would be assumed to lie in the base's CRS.
void check_inset_georeferencing(GDALDatasetH src, const std::string& path) {
  double gt[6];
  const char* wkt = GDALGetProjectionRef(src);
  if (GDALGetGeoTransform(src, gt) != CE_None || !wkt || !*wkt)
    throw InputError(fmt::format(
        "{}: an inset needs georeferencing with a CRS (set one with gdal_edit.py -a_srs)", path));
}

// The value an untagged inset uses for its holes, as the base loader detects
// them (a typical sentinel as its lowest value on at least 0.1% of pixels);
// warns on stderr when one is found. Empty when tagged or none.
std::string untagged_sentinel(GDALDatasetH src, const std::string& path) {
  GDALRasterBandH band = GDALGetRasterBand(src, 1);
  int has_nodata = 0;
  GDALGetRasterNoDataValue(band, &has_nodata);
  if (has_nodata) return {};
  double minmax[2] = {0, 0};
  if (GDALComputeRasterMinMax(band, FALSE, minmax) != CE_None) return {};
  for (double sentinel : {-32768.0, -32767.0, -9999.0}) {
    if (minmax[0] != sentinel) continue;
    GUIntBig hist[1] = {0};
    GDALGetRasterHistogramEx(band, sentinel - 0.5, sentinel + 0.5, 1, hist, FALSE, FALSE, nullptr,
                             nullptr);
    const double pixels = double(GDALGetRasterXSize(src)) * GDALGetRasterYSize(src);
    if (double(hist[0]) * 1000 < pixels) return {};
    fmt::print(stderr,
               "terrasprite: warning: {}: {} pixels hold {:g}, a typical nodata sentinel, but the "
               "inset tags no nodata; treating them as holes\n",
               path, hist[0], sentinel);
    return fmt::format("{:g}", sentinel);
  }
  return {};
}

// The inset warped into `wkt` (bilinear, its own resolution), NaN where it has no data.
Warped warp(const InsetSpec& s, const std::string& wkt) {
  detail::ensure_gdal();
  detail::GdalErrorCapture capture;
  GDALDatasetH src =
      GDALOpenEx(s.path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  if (!src) throw InputError(fmt::format("{}: cannot open: {}", s.path, capture.last()));
  try {
    check_inset_georeferencing(src, s.path);
  } catch (...) {
    GDALClose(src);
    throw;
  }
  const std::string sentinel = untagged_sentinel(src, s.path);
  std::vector<const char*> argv = {"-of",      "MEM", "-t_srs",  wkt.c_str(),  "-r",
                                   "bilinear", "-ot", "Float32", "-dstnodata", "nan"};
  if (!sentinel.empty()) argv.insert(argv.end(), {"-srcnodata", sentinel.c_str()});
  argv.push_back(nullptr);
  GDALWarpAppOptions* opts = GDALWarpAppOptionsNew(const_cast<char**>(argv.data()), nullptr);
  if (!opts) {
    GDALClose(src);
    throw InputError(fmt::format("{}: cannot set up the reprojection: {}", s.path, capture.last()));
  }
  int usage_error = 0;
  GDALDatasetH out = GDALWarp("", nullptr, 1, &src, opts, &usage_error);
  GDALWarpAppOptionsFree(opts);
  GDALClose(src);
  if (!out)
    throw InputError(
        fmt::format("{}: cannot reproject into the base's CRS: {}", s.path, capture.last()));
  Warped r;
  r.w = GDALGetRasterXSize(out);
  r.h = GDALGetRasterYSize(out);
  GDALGetGeoTransform(out, r.gt);
  r.v.resize(std::size_t(r.w) * r.h);
  const CPLErr e = GDALRasterIO(GDALGetRasterBand(out, 1), GF_Read, 0, 0, r.w, r.h, r.v.data(), r.w,
                                r.h, GDT_Float32, 0, 0);
  GDALClose(out);
  if (e != CE_None) throw InputError(fmt::format("{}: cannot read: {}", s.path, capture.last()));
  return r;
}

}  // namespace detail

InsetSpec parse_inset(const std::string& arg) {
  InsetSpec s;
  s.path = arg;
  const auto at = arg.rfind(":blend=");
  if (at != std::string::npos) {
    s.path = arg.substr(0, at);
    const std::string n = arg.substr(at + 7);
    std::size_t used = 0;
    try {
      s.blend = std::stoi(n, &used);
    } catch (...) {
      used = 0;
    }
    if (used != n.size() || n.empty() || s.blend < 0 || s.blend > 1024)
      throw InputError(
          fmt::format("--inset {}: blend must be a whole number of samples 0..1024", arg));
  }
  if (s.path.empty()) throw InputError(fmt::format("--inset {}: no file", arg));
  return s;
}

std::pair<int, int> raster_size(const std::string& path) {
  detail::ensure_gdal();
  detail::GdalErrorCapture capture;
  GDALDatasetH ds =
      GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  if (!ds) throw InputError(fmt::format("{}: cannot open: {}", path, capture.last()));
  const std::pair<int, int> r{GDALGetRasterXSize(ds), GDALGetRasterYSize(ds)};
  GDALClose(ds);
  return r;
}

GridGeo grid_geo(const Heightfield& hf, int source_w, int source_h) {
  if (!hf.geo || hf.geo->wkt.empty())
    throw InputError(
        fmt::format("{}: insets need a base with georeferencing and a CRS (--dem FILE)", hf.name));
  const double* gt = hf.geo->gt;
  GridGeo g;
  g.wkt = hf.geo->wkt;
  g.x0 = gt[0] + 0.5 * gt[1];
  g.y0 = gt[3] + 0.5 * gt[5];
  g.dx = hf.width > 1 ? gt[1] * (source_w - 1) / (hf.width - 1) : gt[1];
  g.dy = hf.height > 1 ? -gt[5] * (source_h - 1) / (hf.height - 1) : -gt[5];
  return g;
}

namespace detail {

InsetResult composite_warped(Heightfield& hf, const GridGeo& g, const InsetSpec& s, const Warped& r,
                             std::vector<float>* weights) {
  const std::vector<float> dist = distance_to_void(r.v, r.w, r.h);
  InsetResult res{s.path, s.blend, 0, 0, {r.gt[1], -r.gt[5]}};
  // Grid samples per inset pixel, so the distance counts grid samples.
  const double per_px = std::min(std::abs(r.gt[1]) / g.dx, std::abs(r.gt[5]) / g.dy);
  // The grid rows and columns the warped inset spans.
  auto u_of = [&](int i) { return (g.x0 + i * g.dx - r.gt[0]) / r.gt[1] - 0.5; };
  auto v_of = [&](int j) { return (g.y0 - j * g.dy - r.gt[3]) / r.gt[5] - 0.5; };
  const int i0 = std::max(0, int(std::ceil((r.gt[0] + 0.5 * r.gt[1] - g.x0) / g.dx)));
  const int i1 =
      std::min(hf.width - 1, int(std::floor((r.gt[0] + (r.w - 0.5) * r.gt[1] - g.x0) / g.dx)));
  const int j0 = std::max(0, int(std::ceil((g.y0 - (r.gt[3] + 0.5 * r.gt[5])) / g.dy)));
  const int j1 =
      std::min(hf.height - 1, int(std::floor((g.y0 - (r.gt[3] + (r.h - 0.5) * r.gt[5])) / g.dy)));
  for (int j = j0; j <= j1; ++j) {
    const double v = v_of(j);
    if (v < 0 || v > r.h - 1) continue;
    const int b = std::min(int(v), std::max(r.h - 2, 0)), b1 = std::min(b + 1, r.h - 1);
    const float fy = float(v - b);
    for (int i = i0; i <= i1; ++i) {
      const double u = u_of(i);
      if (u < 0 || u > r.w - 1) continue;
      const int a = std::min(int(u), std::max(r.w - 2, 0)), a1 = std::min(a + 1, r.w - 1);
      const float fx = float(u - a);
      auto at = [&](const std::vector<float>& p, int x, int y) {
        return p[std::size_t(y) * r.w + x];
      };
      const float q[4] = {at(r.v, a, b), at(r.v, a1, b), at(r.v, a, b1), at(r.v, a1, b1)};
      if (std::isnan(q[0]) || std::isnan(q[1]) || std::isnan(q[2]) || std::isnan(q[3])) continue;
      auto lerp2 = [&](const std::vector<float>& p) {
        const float top = at(p, a, b) + (at(p, a1, b) - at(p, a, b)) * fx;
        const float bot = at(p, a, b1) + (at(p, a1, b1) - at(p, a, b1)) * fx;
        return top + (bot - top) * fy;
      };
      // 0 at the outermost pixel centres with data, in grid samples.
      const double d = std::max(0.0, double(lerp2(dist)) - 1.0) * per_px;
      const float wgt = s.blend == 0 ? 1.f : float(std::min(1.0, d / s.blend));
      if (wgt <= 0.f) continue;
      float& hgt = hf.at(i, j);
      hgt += wgt * (lerp2(r.v) - hgt);
      if (weights) {
        float& m = (*weights)[std::size_t(j) * hf.width + i];
        m = std::max(m, wgt);
      }
      ++res.samples_replaced;
      res.samples_full += wgt >= 1.f;
    }
  }
  return res;
}

}  // namespace detail

std::vector<InsetResult> composite_insets(Heightfield& hf, const GridGeo& g,
                                          const std::vector<InsetSpec>& insets) {
  std::vector<InsetResult> results;
  for (const InsetSpec& s : insets) {
    const InsetResult res = detail::composite_warped(hf, g, s, detail::warp(s, g.wkt), nullptr);
    if (res.samples_replaced == 0)
      throw InputError(
          fmt::format("{}: covers no sample of the base terrain (after reprojection)", s.path));
    results.push_back(res);
  }
  return results;
}

}  // namespace terrasprite
