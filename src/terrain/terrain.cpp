// SPDX-License-Identifier: MIT
// The terrain pipeline's first stage: heights from a file or the generator,
// resampling, exaggeration, then the drape texture registered over them.
#include "terrasprite/terrain.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "terrasprite/error.h"
#include "terrasprite/terrain_gen.h"

namespace terrasprite {
namespace {

// Where the height samples' extent lies in a georeferenced texture (both
// rasters pixel-is-area, sample k at pixel centre k + 0.5).
std::array<double, 4> georegistered_rect(const GeoTransform& hg, int hw, int hh,
                                         const GeoTransform& tg, int tw, int th) {
  double x0 = hg.gt[0] + 0.5 * hg.gt[1], y0 = hg.gt[3] + 0.5 * hg.gt[5];
  double x1 = hg.gt[0] + (hw - 0.5) * hg.gt[1], y1 = hg.gt[3] + (hh - 0.5) * hg.gt[5];
  double u0 = (x0 - tg.gt[0]) / (tw * tg.gt[1]), u1 = (x1 - tg.gt[0]) / (tw * tg.gt[1]);
  double v0 = (y0 - tg.gt[3]) / (th * tg.gt[5]), v1 = (y1 - tg.gt[3]) / (th * tg.gt[5]);
  return {u0, v0, u1 - u0, v1 - v0};
}

void check_options(const TerrainOptions& o) {
  if (!(o.z_scale != 0) || !std::isfinite(o.z_scale))
    throw InputError(fmt::format("--z-scale {}: must be a non-zero number", o.z_scale));
  if (!(o.exaggeration > 0) || o.exaggeration > 1000)
    throw InputError(fmt::format("--exaggeration {}: must be in (0, 1000]", o.exaggeration));
  if (o.spacing && (!(*o.spacing > 0) || *o.spacing > 1e6))
    throw InputError(fmt::format("--spacing {}: must be in (0, 1e6] metres", *o.spacing));
  if (o.resample != 0 && (o.resample < 2 || o.resample > 16385))
    throw InputError(fmt::format("--resample {}: must be between 2 and 16385 samples", o.resample));
}

}  // namespace

Terrain load_terrain(const TerrainOptions& o, std::vector<std::string>* warnings) {
  check_options(o);
  Terrain t;
  if (o.dem.empty()) {
    SynthOptions s;
    s.size = o.synthetic_size;
    s.seed = o.seed;
    s.erosion_passes = o.erosion_passes;
    t.heights = synthesize_terrain(s);
  } else {
    t.heights = load_dem(o, warnings);
  }
  const Heightfield source = t.heights;  // before resampling, for georegistration
  if (o.resample) t.heights = resample_heightfield(t.heights, o.resample, o.resample);
  if (o.exaggeration != 1.0)
    for (float& h : t.heights.heights) h = float(h * o.exaggeration);

  const std::string& tex = o.texture;
  if (tex.empty() || tex == "derived") {
    // Twice the sample density (capped) keeps the shading crisp between samples.
    int tw = std::clamp(2 * (t.heights.width - 1), 2, 4096),
        th = std::clamp(2 * (t.heights.height - 1), 2, 4096);
    t.texture = derived_texture(t.heights, tw, th);
    t.texture_name = "derived";
  } else if (tex == "checker") {
    t.texture = checker_texture(32, 1024);
    t.texture_name = "checker";
  } else {
    t.texture = load_image(tex);
    t.texture_name = tex;
    if (source.geo && t.texture.geo && !source.geo->wkt.empty() &&
        source.geo->wkt == t.texture.geo->wkt)
      t.tex_rect = georegistered_rect(*source.geo, source.width, source.height, *t.texture.geo,
                                      t.texture.width, t.texture.height);
  }
  return t;
}

}  // namespace terrasprite
