// SPDX-License-Identifier: MIT
// Writes the ray caster's pyramid as Cloud-Optimized GeoTIFFs. GDAL's COG
// driver is CreateCopy-only and builds area-aligned overviews of its own; we
// hand it a VRT whose bands view the pyramid in memory (MEM datasets over our
// buffers) and whose <Overview> elements are our vertex-aligned levels, and
// ask it to keep them (OVERVIEWS=FORCE_USE_EXISTING): the file's overview k
// is level k + 1 exactly, whatever its size.
#include <fmt/format.h>
#include <gdal_priv.h>

#include <limits>
#include <string>
#include <vector>

#include "stream/tile_set_json.h"
#include "terrain/gdal_util.h"
#include "terrasprite/error.h"
#include "terrasprite/tiled_terrain.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {
namespace {

// A raster in memory: w x h elements of `type`, `bands` bytes-interleaved
// bands at `pixel_bytes` apart (a packed RGBA colour: 4 bands of 1 byte).
struct MemRaster {
  const void* data = nullptr;
  int w = 0, h = 0;
  const char* type = "Float32";
  int bands = 1, pixel_bytes = 4;
};

std::string mem_name(const MemRaster& r) {
  return fmt::format(
      "MEM:::DATAPOINTER={},PIXELS={},LINES={},BANDS={},DATATYPE={},PIXELOFFSET={},"
      "LINEOFFSET={},BANDOFFSET={}",
      fmt::ptr(r.data), r.w, r.h, r.bands, r.type, r.pixel_bytes,
      std::ptrdiff_t(r.w) * r.pixel_bytes, r.bands > 1 ? 1 : 0);
}

// VRT text: `levels[0]` as the raster, the rest as its overviews; `out_bands`
// of each MEM raster's bands.
std::string vrt_xml(const std::vector<MemRaster>& levels, int out_bands,
                    const std::optional<GeoTransform>& geo) {
  const MemRaster& base = levels[0];
  std::string x =
      fmt::format("<VRTDataset rasterXSize=\"{}\" rasterYSize=\"{}\">\n", base.w, base.h);
  if (geo) {
    const double* g = geo->gt;
    x += fmt::format(
        "<GeoTransform>{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}</GeoTransform>\n", g[0],
        g[1], g[2], g[3], g[4], g[5]);
    if (!geo->wkt.empty()) {
      std::string wkt;
      for (char c : geo->wkt)
        wkt += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
      x += "<SRS>" + wkt + "</SRS>\n";
    }
  }
  for (int b = 1; b <= out_bands; ++b) {
    x += fmt::format("<VRTRasterBand dataType=\"{}\" band=\"{}\">\n", base.type, b);
    if (out_bands == 3)
      x += fmt::format("<ColorInterp>{}</ColorInterp>\n", b == 1   ? "Red"
                                                          : b == 2 ? "Green"
                                                                   : "Blue");
    x += fmt::format(
        "<SimpleSource><SourceFilename relativeToVRT=\"0\">{}</SourceFilename><SourceBand>{}</"
        "SourceBand></SimpleSource>\n",
        mem_name(base), b);
    for (std::size_t k = 1; k < levels.size(); ++k)
      x += fmt::format(
          "<Overview><SourceFilename relativeToVRT=\"0\">{}</SourceFilename><SourceBand>{}</"
          "SourceBand></Overview>\n",
          mem_name(levels[k]), b);
    x += "</VRTRasterBand>\n";
  }
  return x + "</VRTDataset>\n";
}

void write_cog(const std::string& vrt, const std::string& path, const CPLStringList& options) {
  detail::GdalErrorCapture capture;
  GDALDatasetH src = GDALOpen(vrt.c_str(), GA_ReadOnly);
  if (!src)
    throw InputError(fmt::format("{}: cannot build the source raster: {}", path, capture.last()));
  GDALDriverH cog = GDALGetDriverByName("COG");
  if (!cog) {
    GDALClose(src);
    throw InputError(fmt::format("{}: this GDAL has no COG driver", path));
  }
  GDALDatasetH out =
      GDALCreateCopy(cog, path.c_str(), src, FALSE, options.List(), nullptr, nullptr);
  GDALClose(src);
  if (!out) throw InputError(fmt::format("{}: GDAL could not write it: {}", path, capture.last()));
  GDALClose(out);
}

CPLStringList common_options(const TileWriteOptions& o) {
  CPLStringList s;
  s.SetNameValue("BLOCKSIZE", std::to_string(1 << o.tile_log2).c_str());
  s.SetNameValue("OVERVIEWS", "FORCE_USE_EXISTING");
  s.SetNameValue("NUM_THREADS", "ALL_CPUS");
  s.SetNameValue("BIGTIFF", "IF_SAFER");
  return s;
}

void check_options(const TileWriteOptions& o) {
  if (o.tile_log2 < 4 || o.tile_log2 > 9)
    throw InputError(fmt::format("tile_size {}: must be 16, 32, ..., 512", 1 << o.tile_log2));
  if (o.color_compress != "JPEG" && o.color_compress != "WEBP" && o.color_compress != "DEFLATE")
    throw InputError(
        fmt::format("color_compress {}: must be JPEG, WEBP or DEFLATE", o.color_compress));
  if (o.height_compress != "DEFLATE" && o.height_compress != "ZSTD")
    throw InputError(fmt::format("height_compress {}: must be DEFLATE or ZSTD", o.height_compress));
  if (o.color_quality < 1 || o.color_quality > 100)
    throw InputError(fmt::format("color_quality {}: must be 1..100", o.color_quality));
}

// `d`'s max pyramid raised by `cell_max` (per level-0 cell, the highest
// sample of a finer surface inside it): each level takes the max over its
// cells, dilated by one cell as the pyramid's own bounds are.
std::vector<MaxLevel> raise_bounds(const VoxelTerrain::Data& d,
                                   const std::vector<float>& cell_max) {
  std::vector<MaxLevel> out = d.maxes;
  if (out.empty() || cell_max.size() != std::size_t(out[0].w) * std::size_t(out[0].h))
    throw InputError("fine levels: the base cell maxima do not match the terrain");
  std::vector<float> raw = cell_max;  // undilated, cells of the current level
  int rw = out[0].w, rh = out[0].h;
  for (std::size_t k = 0; k < out.size(); ++k) {
    MaxLevel& m = out[k];
    if (k > 0) {  // halve: a cell of level k covers 2 x 2 cells of level k - 1
      std::vector<float> next(std::size_t(m.w) * m.h, -std::numeric_limits<float>::infinity());
      for (int b = 0; b < rh; ++b)
        for (int a = 0; a < rw; ++a) {
          float& c = next[std::size_t(std::min(b / 2, m.h - 1)) * m.w + std::min(a / 2, m.w - 1)];
          c = std::max(c, raw[std::size_t(b) * rw + a]);
        }
      raw.swap(next);
      rw = m.w;
      rh = m.h;
    }
    for (int b = 0; b < m.h; ++b)
      for (int a = 0; a < m.w; ++a) {
        float v = -std::numeric_limits<float>::infinity();
        for (int y = std::max(0, b - 1); y <= std::min(m.h - 1, b + 1); ++y)
          for (int x = std::max(0, a - 1); x <= std::min(m.w - 1, a + 1); ++x)
            v = std::max(v, raw[std::size_t(y) * rw + x]);
        float& bd = m.bound[std::size_t(b) * m.w + a];
        bd = std::max(bd, v);
      }
  }
  return out;
}

}  // namespace

void write_tiled_terrain(const VoxelTerrain& terrain, const std::optional<GeoTransform>& geo,
                         const std::string& dir, const TileWriteOptions& o) {
  check_options(o);
  detail::ensure_gdal();
  const VoxelTerrain::Data& d = terrain.data();
  if (!d.has_area()) throw InputError(fmt::format("{}: the terrain has no area to tile", dir));

  std::vector<MemRaster> heights, colors, bounds;
  for (const PyramidLevel& l : d.levels) {
    heights.push_back({l.height.data(), l.w, l.h, "Float32", 1, 4});
    colors.push_back({l.color.data(), l.w, l.h, "Byte", 4, 4});
  }
  // Fine levels: the base's bounds raised to cover the inset's samples.
  const std::vector<MaxLevel> raised =
      o.fine ? raise_bounds(d, o.fine->base_cell_max) : std::vector<MaxLevel>{};
  const std::vector<MaxLevel>& maxes = o.fine ? raised : d.maxes;
  std::vector<const float*> bound_data;
  for (const MaxLevel& m : maxes) {
    bounds.push_back({m.bound.data(), m.w, m.h, "Float32", 1, 4});
    bound_data.push_back(m.bound.data());
  }

  CPLStringList ho = common_options(o);
  ho.SetNameValue("COMPRESS", o.height_compress.c_str());
  ho.SetNameValue("PREDICTOR", "YES");  // 3 (floating point) for Float32
  write_cog(vrt_xml(heights, 1, geo), dir + "/height.tif", ho);
  // Bounds of cell (a, b) sit between samples; the cell grid is offset by
  // half a cell, so it carries no georeferencing of its own.
  write_cog(vrt_xml(bounds, 1, std::nullopt), dir + "/bound.tif", ho);
  CPLStringList co = common_options(o);
  co.SetNameValue("COMPRESS", o.color_compress.c_str());
  if (o.color_compress != "DEFLATE")
    co.SetNameValue("QUALITY", std::to_string(o.color_quality).c_str());
  write_cog(vrt_xml(colors, 3, geo), dir + "/color.tif", co);

  write_tile_set_json(terrain, bound_data, geo, o, dir + "/tiles.json");
}

}  // namespace terrasprite
