// SPDX-License-Identifier: MIT
// A drape texture registered over the height samples: where its georeferenced
// footprint lies (transformed between CRSs when they differ), how much of the
// terrain it covers, and what shows where the image itself has no data.
#include "terrain/drape.h"

#include <fmt/format.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/texture_gen.h"

namespace terrasprite::detail {
namespace {

struct Srs {
  OGRSpatialReferenceH h = nullptr;
  explicit Srs(const std::string& wkt) : h(OSRNewSpatialReference(wkt.c_str())) {
    if (h) OSRSetAxisMappingStrategy(h, OAMS_TRADITIONAL_GIS_ORDER);  // x = east, y = north
  }
  ~Srs() {
    if (h) OSRDestroySpatialReference(h);
  }
};

// The heights' sample-centre corners (pixel-is-area: sample k at pixel k + 0.5),
// in the texture's CRS; false when the CRSs cannot be related.
bool corners_in_texture_crs(const GeoTransform& hg, int hw, int hh, const GeoTransform& tg,
                            double xs[4], double ys[4]) {
  const double is[4] = {0.5, hw - 0.5, 0.5, hw - 0.5}, js[4] = {0.5, 0.5, hh - 0.5, hh - 0.5};
  for (int k = 0; k < 4; ++k) {
    xs[k] = hg.gt[0] + is[k] * hg.gt[1] + js[k] * hg.gt[2];
    ys[k] = hg.gt[3] + is[k] * hg.gt[4] + js[k] * hg.gt[5];
  }
  if (hg.wkt == tg.wkt) return true;
  Srs from(hg.wkt), to(tg.wkt);
  if (!from.h || !to.h) return false;
  OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(from.h, to.h);
  if (!ct) return false;
  int ok[4] = {0, 0, 0, 0};
  const bool done = OCTTransformEx(ct, 4, xs, ys, nullptr, ok) && ok[0] && ok[1] && ok[2] && ok[3];
  OCTDestroyCoordinateTransformation(ct);
  return done;
}

}  // namespace

std::optional<std::array<double, 4>> georegistered_rect(const GeoTransform& hg, int hw, int hh,
                                                        const GeoTransform& tg, int tw, int th) {
  double xs[4], ys[4];
  if (!corners_in_texture_crs(hg, hw, hh, tg, xs, ys)) return std::nullopt;
  // Texture pixel coordinates of each corner (the texture is north-up or flipped, never rotated).
  double us[4], vs[4];
  for (int k = 0; k < 4; ++k) {
    us[k] = (xs[k] - tg.gt[0]) / (tw * tg.gt[1]);
    vs[k] = (ys[k] - tg.gt[3]) / (th * tg.gt[5]);
  }
  // Corners 0 (north-west) and 3 (south-east) span the rectangle; a CRS change
  // bends it slightly, which the mean of the opposite corners absorbs.
  const double u0 = 0.5 * (us[0] + us[2]), u1 = 0.5 * (us[1] + us[3]);
  const double v0 = 0.5 * (vs[0] + vs[1]), v1 = 0.5 * (vs[2] + vs[3]);
  if (!(std::isfinite(u0) && std::isfinite(u1) && std::isfinite(v0) && std::isfinite(v1)))
    return std::nullopt;
  return std::array<double, 4>{u0, v0, u1 - u0, v1 - v0};
}

double covered_fraction(const std::array<double, 4>& r) {
  auto overlap = [](double a, double len) {
    const double lo = std::min(a, a + len), hi = std::max(a, a + len);
    return std::max(0.0, std::min(hi, 1.0) - std::max(lo, 0.0)) / std::max(hi - lo, 1e-300);
  };
  return overlap(r[0], r[2]) * overlap(r[1], r[3]);
}

long long fill_transparent_texels(Image& texture, const std::array<double, 4>& rect,
                                  const HeightSampler& heights) {
  long long holes = 0;
  for (std::size_t p = 3; p < texture.rgba.size(); p += 4) holes += texture.rgba[p] == 0;
  if (!holes) return 0;
  // The derived texture spans the terrain exactly: terrain (s, t) is its (u, v).
  const int dw = std::clamp(2 * (heights.width - 1), 2, 2048),
            dh = std::clamp(2 * (heights.height - 1), 2, 2048);
  const Image derived = derived_texture(heights, dw, dh);
  for (int y = 0; y < texture.height; ++y)
    for (int x = 0; x < texture.width; ++x) {
      std::uint8_t* px = texture.px(x, y);
      if (px[3] != 0) continue;
      const double u = (x + 0.5) / texture.width, v = (y + 0.5) / texture.height;
      const double s = std::clamp((u - rect[0]) / rect[2], 0.0, 1.0),
                   t = std::clamp((v - rect[1]) / rect[3], 0.0, 1.0);
      const std::uint8_t* d =
          derived.px(std::min(int(s * dw), dw - 1), std::min(int(t * dh), dh - 1));
      std::copy(d, d + 3, px);
      px[3] = 255;
    }
  return holes;
}

}  // namespace terrasprite::detail
