// SPDX-License-Identifier: MIT
// The terrain pipeline's first stage: heights from a file or the generator,
// resampling, exaggeration, then the drape texture registered over them.
#include "terrasprite/terrain.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "terrain/drape.h"
#include "terrasprite/error.h"
#include "terrasprite/terrain_gen.h"

namespace terrasprite {
namespace {

// Registers a loaded texture over the heights: by georeferencing when both
// have it, refused when it covers none of the terrain, warned when under half;
// the image's own nodata (alpha 0) shows the derived texture.
void register_drape(Terrain& t, const Heightfield& source, const std::string& dem,
                    std::vector<std::string>* warnings) {
  const Image& tex = t.texture;
  if (source.geo && tex.geo && !source.geo->wkt.empty() && !tex.geo->wkt.empty()) {
    if (auto rect = detail::georegistered_rect(*source.geo, source.width, source.height, *tex.geo,
                                               tex.width, tex.height)) {
      const double covered = detail::covered_fraction(*rect);
      if (covered <= 0)
        throw InputError(
            fmt::format("{}: its georeferenced footprint does not overlap the heights of {} at all",
                        t.texture_name, dem));
      if (covered < 0.5 && warnings)
        warnings->push_back(fmt::format(
            "{}: covers only {:.0f}% of the heights of {}; the rest is drawn with its edge colours",
            t.texture_name, covered * 100, dem));
      t.tex_rect = *rect;
    } else if (warnings) {
      warnings->push_back(fmt::format(
          "{}: its CRS cannot be related to that of {}; stretched over the terrain instead",
          t.texture_name, dem));
    }
  }
  detail::fill_transparent_texels(t.texture, t.tex_rect, t.heights);
}

// Bounds on what a terrain may be. Heights: beyond 10,000 km from sea level
// is an encoding or unit mistake; spacing: a micrometre to 1,000 km per sample.
constexpr double kMaxAbsHeightM = 1e7;
constexpr double kMinSpacingM = 1e-6, kMaxSpacingM = 1e6;
// The synthetic grid's full-resolution mesh must fit the renderer's 4 GiB of
// buffers (about 48 bytes a sample): 8193 x 8193 is the largest power of two
// plus one that does. Erosion costs one pass over the grid each.
constexpr int kMaxSyntheticSize = 8193, kMaxErosionPasses = 100;

void check_options(const TerrainOptions& o) {
  if (o.dem.empty() && o.dem_given)
    throw InputError("dem \"\": empty file name (no DEM means the synthetic terrain)");
  if (o.synthetic_size < 2 || o.synthetic_size > kMaxSyntheticSize)
    throw InputError(fmt::format("synthetic_size {}: must be between 2 and {} samples",
                                 o.synthetic_size, kMaxSyntheticSize));
  if (o.erosion_passes < 0 || o.erosion_passes > kMaxErosionPasses)
    throw InputError(fmt::format("erosion_passes {}: must be between 0 and {} passes",
                                 o.erosion_passes, kMaxErosionPasses));
  if (!(o.z_scale != 0) || !std::isfinite(o.z_scale))
    throw InputError(fmt::format("z_scale {}: must be a non-zero number", o.z_scale));
  if (!(o.exaggeration > 0) || o.exaggeration > 1000)
    throw InputError(fmt::format("exaggeration {}: must be in (0, 1000]", o.exaggeration));
  if (o.spacing && !(*o.spacing >= kMinSpacingM && *o.spacing <= kMaxSpacingM))
    throw InputError(fmt::format("spacing_m {}: must be between {:g} and {:g} metres", *o.spacing,
                                 kMinSpacingM, kMaxSpacingM));
  if (o.resample != 0 && (o.resample < 2 || o.resample > 16385))
    throw InputError(fmt::format("resample {}: must be between 2 and 16385 samples", o.resample));
}

// After every scale and offset: finite heights within bounds, a real extent.
void check_heights(const Heightfield& h) {
  if (!(h.spacing_x >= kMinSpacingM && h.spacing_x <= kMaxSpacingM && h.spacing_y >= kMinSpacingM &&
        h.spacing_y <= kMaxSpacingM))
    throw InputError(
        fmt::format("{}: sample spacing {:g} x {:g} m is outside {:g} .. {:g} m (give --spacing)",
                    h.name, h.spacing_x, h.spacing_y, kMinSpacingM, kMaxSpacingM));
  for (std::size_t p = 0; p < h.heights.size(); ++p)
    if (!(std::abs(h.heights[p]) <= kMaxAbsHeightM))
      throw InputError(fmt::format(
          "{}: height {} at sample ({}, {}) after scale, offset and --z-scale is not a finite "
          "height within {:g} m",
          h.name, h.heights[p], p % h.width, p / h.width, kMaxAbsHeightM));
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
  check_heights(t.heights);
  const Heightfield source = t.heights;  // before resampling, for georegistration
  if (o.resample) t.heights = resample_heightfield(t.heights, o.resample, o.resample);
  if (o.exaggeration != 1.0) {
    for (float& h : t.heights.heights) h = float(h * o.exaggeration);
    check_heights(t.heights);
  }

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
    register_drape(t, source, source.name, warnings);
  }
  return t;
}

}  // namespace terrasprite
