// SPDX-License-Identifier: MIT
// The terrain pipeline's first stage: heights from a file or the generator,
// resampling, exaggeration, then the drape texture registered over them.
#include "terrasprite/terrain/terrain.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "terrain/drape.h"
#include "terrain/grid_sample.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/dem_loader.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/terrain/resample.h"
#include "terrasprite/terrain/synth.h"
#include "terrasprite/terrain/texture_gen.h"

namespace terrasprite {
namespace {

// Registers a loaded texture over the heights: by georeferencing when both
// have it, refused when it covers none of the terrain, warned when under half;
// the image's own nodata (alpha 0) shows the derived texture of `heights`
// (the final grid).
void register_drape(Image& tex, std::array<double, 4>& tex_rect, const std::string& texture_name,
                    const Heightfield& source, const HeightSampler& heights, const std::string& dem,
                    std::vector<std::string>* warnings) {
  if (source.geo && tex.geo && !source.geo->wkt.empty() && !tex.geo->wkt.empty()) {
    if (auto rect = detail::georegistered_rect(*source.geo, source.width, source.height, *tex.geo,
                                               tex.width, tex.height)) {
      const double covered = detail::covered_fraction(*rect);
      if (covered <= 0)
        throw InputError(
            fmt::format("{}: its georeferenced footprint does not overlap the heights of {} at all",
                        texture_name, dem));
      if (covered < 0.5 && warnings)
        warnings->push_back(fmt::format(
            "{}: covers only {:.0f}% of the heights of {}; the rest is drawn with its edge colours",
            texture_name, covered * 100, dem));
      tex_rect = *rect;
    } else if (warnings) {
      warnings->push_back(fmt::format(
          "{}: its CRS cannot be related to that of {}; stretched over the terrain instead",
          texture_name, dem));
    }
  }
  detail::fill_transparent_texels(tex, tex_rect, heights);
}

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
  check_spacing(h.name, h.spacing_x, h.spacing_y);
  for (std::size_t p = 0; p < h.heights.size(); ++p)
    if (!(std::abs(h.heights[p]) <= kMaxAbsHeightM))
      throw InputError(fmt::format(
          "{}: height {} at sample ({}, {}) after scale, offset and --z-scale is not a finite "
          "height within {:g} m",
          h.name, h.heights[p], p % h.width, p / h.width, kMaxAbsHeightM));
}

// The heights as given (synthesised or read), checked, before --resample.
Heightfield load_source_heights(const TerrainOptions& o, std::vector<std::string>* warnings) {
  Heightfield h;
  if (o.dem.empty()) {
    SynthOptions s;
    s.size = o.synthetic_size;
    s.seed = o.seed;
    s.erosion_passes = o.erosion_passes;
    h = synthesize_terrain(s);
  } else {
    h = load_dem(o, warnings);
  }
  check_heights(h);
  return h;
}

// The drape texture of the final grid `heights` (load_terrain's choice).
void make_texture(const TerrainOptions& o, const Heightfield& source, const HeightSampler& heights,
                  Image& texture, std::array<double, 4>& tex_rect, std::string& texture_name,
                  std::vector<std::string>* warnings) {
  const std::string& tex = o.texture;
  if (tex.empty() || tex == "derived") {
    // Twice the sample density (capped) keeps the shading crisp between samples.
    int tw = std::clamp(2 * (heights.width - 1), 2, 4096),
        th = std::clamp(2 * (heights.height - 1), 2, 4096);
    texture = derived_texture(heights, tw, th);
    texture_name = "derived";
  } else if (tex == "checker") {
    texture = checker_texture(32, 1024);
    texture_name = "checker";
  } else {
    texture = load_image(tex);
    texture_name = tex;
    register_drape(texture, tex_rect, texture_name, source, heights, source.name, warnings);
  }
}

// Blends kVoidTint half over the texels whose nearest height sample was nodata.
void tint_voids(Image& tex, const std::array<double, 4>& rect, const Heightfield& h) {
  if (h.voids.empty() || tex.empty()) return;
  for (int y = 0; y < tex.height; ++y)
    for (int x = 0; x < tex.width; ++x) {
      const double s = ((x + 0.5) / tex.width - rect[0]) / rect[2];
      const double t = ((y + 0.5) / tex.height - rect[1]) / rect[3];
      if (s < 0 || s > 1 || t < 0 || t > 1) continue;
      const long i = std::lround(s * (h.width - 1)), j = std::lround(t * (h.height - 1));
      if (!h.voids[std::size_t(j) * h.width + i]) continue;
      std::uint8_t* p = tex.px(x, y);
      for (int c = 0; c < 3; ++c) p[c] = std::uint8_t((p[c] + kVoidTint[std::size_t(c)] + 1) / 2);
    }
}

}  // namespace

void check_spacing(const std::string& name, double spacing_x, double spacing_y) {
  auto ok = [](double s) { return s >= kMinSpacingM && s <= kMaxSpacingM; };
  if (!ok(spacing_x) || !ok(spacing_y))
    throw InputError(
        fmt::format("{}: sample spacing {:g} x {:g} m is outside {:g} .. {:g} m (give --spacing)",
                    name, spacing_x, spacing_y, kMinSpacingM, kMaxSpacingM));
}

void check_height_range(const std::string& name, double lowest, double highest,
                        const std::string& hint) {
  if (!(std::abs(lowest) <= kMaxAbsHeightM && std::abs(highest) <= kMaxAbsHeightM &&
        lowest <= highest))
    throw InputError(
        fmt::format("{}: heights {:g} .. {:g} m are not finite heights within {:g} m{}", name,
                    lowest, highest, kMaxAbsHeightM, hint.empty() ? "" : "; " + hint));
}

Terrain load_terrain(const TerrainOptions& o, std::vector<std::string>* warnings) {
  check_options(o);
  Terrain t;
  t.heights = load_source_heights(o, warnings);
  const Heightfield source = t.heights;  // before resampling, for georegistration
  if (o.resample) t.heights = resample_heightfield(t.heights, o.resample, o.resample);
  if (o.exaggeration != 1.0) {
    for (float& h : t.heights.heights) h = float(h * o.exaggeration);
    check_heights(t.heights);
  }

  make_texture(o, source, height_sampler(t.heights), t.texture, t.tex_rect, t.texture_name,
               warnings);
  if (o.show_voids) tint_voids(t.texture, t.tex_rect, t.heights);
  return t;
}

float LargeTerrain::at(int i, int j) const {
  float v;
  if (resampled) {  // resample_heightfield's grid: the same extent, corners on corners
    const double x = (i - (width - 1) * 0.5) * spacing_x, y = ((height - 1) * 0.5 - j) * spacing_y;
    v = source.sample(x, y);
  } else {
    v = source.at(i, j);
  }
  return exaggeration != 1.0 ? float(v * exaggeration) : v;
}

void LargeTerrain::row(int j, float* out) const {
  for (int i = 0; i < width; ++i) out[i] = at(i, j);
}

HeightSampler LargeTerrain::sampler() const {
  HeightSampler s;
  s.sample = [this](double x, double y) {
    return detail::sample_grid(width, height, spacing_x, spacing_y, x, y,
                               [this](int i, int j) { return at(i, j); });
  };
  s.width = width;
  s.height = height;
  s.spacing_x = spacing_x;
  s.spacing_y = spacing_y;
  s.min_height = min_height;
  s.max_height = max_height;
  return s;
}

namespace {

// One pass over the final grid, computed row by row: its height range, and
// check_heights' test of every sample (the first bad one in row order named).
void scan_heights(LargeTerrain& t) {
  const std::size_t rows = std::size_t(t.height);
  std::vector<float> lo(rows), hi(rows);
  std::vector<int> bad(rows, -1);
  tbb::parallel_for(0, t.height, [&](int j) {
    std::vector<float> r(std::size_t(t.width));
    t.row(j, r.data());
    float a = r[0], b = r[0];
    for (int i = 0; i < t.width; ++i) {
      if (!(std::abs(r[std::size_t(i)]) <= kMaxAbsHeightM) && bad[std::size_t(j)] < 0)
        bad[std::size_t(j)] = i;
      a = std::min(a, r[std::size_t(i)]);
      b = std::max(b, r[std::size_t(i)]);
    }
    lo[std::size_t(j)] = a;
    hi[std::size_t(j)] = b;
  });
  for (int j = 0; j < t.height; ++j)
    if (bad[std::size_t(j)] >= 0)
      throw InputError(fmt::format(
          "{}: height {} at sample ({}, {}) after scale, offset and --z-scale is not a finite "
          "height within {:g} m",
          t.source.name, t.at(bad[std::size_t(j)], j), bad[std::size_t(j)], j, kMaxAbsHeightM));
  t.min_height = *std::min_element(lo.begin(), lo.end());
  t.max_height = *std::max_element(hi.begin(), hi.end());
}

}  // namespace

LargeTerrain load_large_terrain(const TerrainOptions& options, std::vector<std::string>* warnings) {
  TerrainOptions o = options;
  o.resample = 0;  // checked here against the larger limit
  check_options(o);
  if (options.resample != 0 && (options.resample < 2 || options.resample > kMaxLargeResample))
    throw InputError(fmt::format("resample {}: must be between 2 and {} samples", options.resample,
                                 kMaxLargeResample));
  LargeTerrain t;
  t.source = load_source_heights(o, warnings);
  t.resampled = options.resample != 0;
  t.width = t.resampled ? options.resample : t.source.width;
  t.height = t.resampled ? options.resample : t.source.height;
  // resample_heightfield's spacing: the same extent over the new sample count.
  t.spacing_x =
      t.resampled && t.width > 1 ? t.source.extent_x() / (t.width - 1) : t.source.spacing_x;
  t.spacing_y =
      t.resampled && t.height > 1 ? t.source.extent_y() / (t.height - 1) : t.source.spacing_y;
  t.exaggeration = o.exaggeration;
  Heightfield shape;  // the final grid's header, for the spacing check
  shape.name = t.source.name;
  shape.width = t.width;
  shape.height = t.height;
  shape.spacing_x = t.spacing_x;
  shape.spacing_y = t.spacing_y;
  check_heights(shape);
  scan_heights(t);
  make_texture(o, t.source, t.sampler(), t.texture, t.tex_rect, t.texture_name, warnings);
  return t;
}

}  // namespace terrasprite
