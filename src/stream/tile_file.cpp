// SPDX-License-Identifier: MIT
#include "stream/tile_file.h"

#include <fmt/format.h>
#include <gdal.h>

#include <algorithm>
#include <limits>

#include "stream/cog_source.h"
#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace {

GDALDatasetH open_or_throw(const std::string& path) {
  detail::GdalErrorCapture capture;
  GDALDatasetH ds =
      GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  if (!ds) throw InputError(fmt::format("{}: cannot open: {}", path, capture.last()));
  return ds;
}

// Band `b` of `ds` at pyramid level `level` (level 0: the raster itself).
GDALRasterBandH level_band(GDALDatasetH ds, int b, int level) {
  GDALRasterBandH band = GDALGetRasterBand(ds, b);
  return level == 0 ? band : GDALGetOverview(band, level - 1);
}

}  // namespace

void tile_window(const TileSetInfo& set, int level, int tx, int ty, int& x0, int& y0, int& w,
                 int& h) {
  const int T = 1 << set.grid.tile_log2;
  x0 = tx * T;
  y0 = ty * T;
  w = std::min(T, set.tiles_cells_w(level) - x0) + 1;
  h = std::min(T, set.tiles_cells_h(level) - y0) + 1;
}

std::size_t tile_bytes(const TileSetInfo& set, int level, int tx, int ty) {
  int x0, y0, w, h;
  tile_window(set, level, tx, ty, x0, y0, w, h);
  const std::size_t n = std::size_t(w) * h, cells = std::size_t(w - 1) * (h - 1);
  return (level <= set.grid.coarsest_level ? n * 8 : 0) + cells * 4 + sizeof(TileData);
}

TileFile::TileFile(const TileSetInfo& set) : set_(set) {
  detail::ensure_gdal();
  if (set.cog) {  // an existing COG: its texture is the colour, bounds are held in memory
    height_ = open_or_throw(set.cog->path);
    if (!set.cog->texture.empty()) color_ = open_or_throw(set.cog->texture);
    return;
  }
  height_ = open_or_throw(set.height_file());
  color_ = open_or_throw(set.color_file());
  bound_ = open_or_throw(set.bound_file());
}

TileFile::~TileFile() {
  for (GDALDatasetH ds : {height_, color_, bound_})
    if (ds) GDALClose(ds);
}

bool TileFile::read(int level, int tx, int ty, TileData& out, std::string& error) {
  int x0, y0, w, h;
  tile_window(set_, level, tx, ty, x0, y0, w, h);
  out.level = level;
  out.tx = tx;
  out.ty = ty;
  if (!read_window(level, x0, y0, w, h, out, error)) return false;
  out.block.x0 += set_.origin_x >> level;  // a fine window set: the enclosing grid's indices
  out.block.y0 += set_.origin_y >> level;
  return true;
}

bool TileFile::read_level(int level, TileData& out, std::string& error) {
  out.level = level;
  out.tx = out.ty = -1;
  return read_window(level, 0, 0, set_.level_w(level), set_.level_h(level), out, error);
}

bool TileFile::read_level_heights(int level, std::vector<float>& out, std::string& error) {
  if (set_.cog) {
    TileData d;
    if (!read_level(level, d, error)) return false;
    out = std::move(d.height);
    return true;
  }
  detail::GdalErrorCapture capture;
  const int w = set_.level_w(level), h = set_.level_h(level);
  out.resize(std::size_t(w) * h);
  GDALRasterBandH hb = level <= set_.grid.coarsest_level ? level_band(height_, 1, level) : nullptr;
  if (!hb ||
      GDALRasterIO(hb, GF_Read, 0, 0, w, h, out.data(), w, h, GDT_Float32, 0, 0) != CE_None) {
    error = fmt::format("heights of level {}: {}", level, capture.last());
    return false;
  }
  return true;
}

bool TileFile::read_window(int level, int x0, int y0, int w, int h, TileData& out,
                           std::string& error) {
  const bool samples = level <= set_.grid.coarsest_level;
  out.height.clear();
  out.color.clear();
  if (set_.cog) {
    if (!read_cog_window(set_, height_, color_, level, x0, y0, w, h, out, error)) return false;
  } else if (!read_tiles_window(level, x0, y0, w, h, out, error)) {
    return false;
  }
  const int cw = std::max(1, w - 1);  // cells: one fewer than samples (at least one)
  TileBlock& t = out.block;
  t = TileBlock{};
  t.height = samples ? out.height.data() : nullptr;
  t.color = samples ? out.color.data() : nullptr;
  t.bound = out.bound.data();
  t.stride = w;
  t.bound_stride = cw;
  t.x0 = x0;
  t.y0 = y0;
  t.w = w;
  t.h = h;
  t.max_height = -std::numeric_limits<float>::infinity();
  for (float v : out.bound) t.max_height = std::max(t.max_height, v);
  return true;
}

bool TileFile::read_tiles_window(int level, int x0, int y0, int w, int h, TileData& out,
                                 std::string& error) {
  detail::GdalErrorCapture capture;
  const bool samples = level <= set_.grid.coarsest_level;
  const std::size_t n = std::size_t(w) * h;
  auto fail = [&](const char* what) {
    error = fmt::format("{} of level {} at ({}, {}): {}", what, level, x0, y0, capture.last());
    return false;
  };
  if (samples) {
    out.height.resize(n);
    GDALRasterBandH hb = level_band(height_, 1, level);
    if (!hb || GDALRasterIO(hb, GF_Read, x0, y0, w, h, out.height.data(), w, h, GDT_Float32, 0,
                            0) != CE_None)
      return fail("height");
    out.color.assign(n, 0xff000000u);
    auto* bytes = reinterpret_cast<std::uint8_t*>(out.color.data());
    for (int b = 0; b < 3; ++b) {
      GDALRasterBandH cb = level_band(color_, b + 1, level);
      if (!cb || GDALRasterIO(cb, GF_Read, x0, y0, w, h, bytes + b, w, h, GDT_Byte, 4,
                              GSpacing(w) * 4) != CE_None)
        return fail("colour");
    }
  }
  const int cw = std::max(1, w - 1), ch = std::max(1, h - 1);
  out.bound.resize(std::size_t(cw) * ch);
  GDALRasterBandH bb = level_band(bound_, 1, level);
  if (!bb || GDALRasterIO(bb, GF_Read, x0, y0, cw, ch, out.bound.data(), cw, ch, GDT_Float32, 0,
                          0) != CE_None)
    return fail("bound");
  return true;
}

}  // namespace terrasprite
