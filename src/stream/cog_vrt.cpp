// SPDX-License-Identifier: MIT
// VRTs over a pyramid's levels, copied by GDAL's COG driver (see cog_vrt.h).
#include "stream/cog_vrt.h"

#include <fmt/format.h>
#include <gdal_priv.h>

#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s)
    out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

// VRT text: `levels[0]` as the raster, the rest as its overviews; `out_bands`
// of each source's bands.
std::string vrt_xml(const std::vector<LevelSource>& levels, const char* type, int out_bands,
                    const std::optional<GeoTransform>& geo) {
  const LevelSource& base = levels[0];
  std::string x =
      fmt::format("<VRTDataset rasterXSize=\"{}\" rasterYSize=\"{}\">\n", base.w, base.h);
  if (geo) {
    const double* g = geo->gt;
    x += fmt::format(
        "<GeoTransform>{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}</GeoTransform>\n", g[0],
        g[1], g[2], g[3], g[4], g[5]);
    if (!geo->wkt.empty()) {
      x += "<SRS>" + xml_escape(geo->wkt) + "</SRS>\n";
    }
  }
  for (int b = 1; b <= out_bands; ++b) {
    x += fmt::format("<VRTRasterBand dataType=\"{}\" band=\"{}\">\n", type, b);
    if (out_bands == 3)
      x += fmt::format("<ColorInterp>{}</ColorInterp>\n", b == 1   ? "Red"
                                                          : b == 2 ? "Green"
                                                                   : "Blue");
    x += fmt::format(
        "<SimpleSource><SourceFilename relativeToVRT=\"0\">{}</SourceFilename><SourceBand>{}</"
        "SourceBand></SimpleSource>\n",
        xml_escape(base.name), b);
    for (std::size_t k = 1; k < levels.size(); ++k)
      x += fmt::format(
          "<Overview><SourceFilename relativeToVRT=\"0\">{}</SourceFilename><SourceBand>{}</"
          "SourceBand></Overview>\n",
          xml_escape(levels[k].name), b);
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

}  // namespace

void check_write_options(const TileWriteOptions& o) {
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

std::string mem_source(const void* data, int w, int h, const char* type, int bands,
                       int pixel_bytes) {
  return fmt::format(
      "MEM:::DATAPOINTER={},PIXELS={},LINES={},BANDS={},DATATYPE={},PIXELOFFSET={},"
      "LINEOFFSET={},BANDOFFSET={}",
      fmt::ptr(data), w, h, bands, type, pixel_bytes, std::ptrdiff_t(w) * pixel_bytes,
      bands > 1 ? 1 : 0);
}

void write_level_cogs(const std::vector<LevelSource>& heights,
                      const std::vector<LevelSource>& colors,
                      const std::vector<LevelSource>& bounds,
                      const std::optional<GeoTransform>& geo, const std::string& dir,
                      const TileWriteOptions& o) {
  CPLStringList ho = common_options(o);
  ho.SetNameValue("COMPRESS", o.height_compress.c_str());
  ho.SetNameValue("PREDICTOR", "YES");  // 3 (floating point) for Float32
  write_cog(vrt_xml(heights, "Float32", 1, geo), dir + "/height.tif", ho);
  // Bounds of cell (a, b) sit between samples; the cell grid is offset by
  // half a cell, so it carries no georeferencing of its own.
  write_cog(vrt_xml(bounds, "Float32", 1, std::nullopt), dir + "/bound.tif", ho);
  CPLStringList co = common_options(o);
  co.SetNameValue("COMPRESS", o.color_compress.c_str());
  if (o.color_compress != "DEFLATE")
    co.SetNameValue("QUALITY", std::to_string(o.color_quality).c_str());
  write_cog(vrt_xml(colors, "Byte", 3, geo), dir + "/color.tif", co);
}

}  // namespace terrasprite
