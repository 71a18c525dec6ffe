// SPDX-License-Identifier: MIT
// The tile writer out of core: the ray caster's pyramids (voxel_pyramid.cpp)
// built row by row, as Cohen-Or et al. preprocess a terrain database larger
// than memory. Level 0 comes in bands of rows; each render level halves the
// finer one as its rows arrive, holding three of them; each bound level
// takes the max over 2 x 2 finer cells and dilates by one cell, holding
// three cell rows. Rows go to tiled temporary GeoTIFFs, copied into the COGs
// at the end (cog_vrt.h).
//
//   level-0 band ──► level 0 ──► level 1 ──► ... ──► coarsest    (render rows)
//                       │
//                       └─► cells 0 ──► cells 1 ──► ... ──► 1 x 1 (bound rows)
#include <fmt/format.h>
#include <gdal_priv.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <limits>
#include <memory>

#include "stream/cog_vrt.h"
#include "stream/tile_set_json.h"
#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/stream/tiled_terrain.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {
namespace {

namespace fs = std::filesystem;

// fn(i0, i1) over column chunks of [0, w), in parallel when the row is long.
template <class Fn>
void for_columns(int w, const Fn& fn) {
  constexpr int kGrain = 4096;
  if (w <= kGrain) return fn(0, w);
  tbb::parallel_for(tbb::blocked_range<int>(0, w, kGrain),
                    [&](const tbb::blocked_range<int>& r) { fn(r.begin(), r.end()); });
}

// A tiled temporary GeoTIFF, written in bands of whole rows (uncompressed:
// it is read once, by the COG copy).
class TempRaster {
 public:
  TempRaster(const std::string& path, int w, int h, GDALDataType type, int bands, int block)
      : path_(path), w_(w), type_(type), bands_(bands) {
    detail::GdalErrorCapture capture;
    CPLStringList o;
    o.SetNameValue("TILED", "YES");
    o.SetNameValue("BLOCKXSIZE", std::to_string(block).c_str());
    o.SetNameValue("BLOCKYSIZE", std::to_string(block).c_str());
    o.SetNameValue("INTERLEAVE", "PIXEL");
    o.SetNameValue("BIGTIFF", "IF_SAFER");
    GDALDriverH gtiff = GDALGetDriverByName("GTiff");
    ds_ = gtiff ? GDALCreate(gtiff, path.c_str(), w, h, bands, type, o.List()) : nullptr;
    if (!ds_) throw InputError(fmt::format("{}: cannot create: {}", path, capture.last()));
  }
  ~TempRaster() { close(); }
  TempRaster(const TempRaster&) = delete;
  TempRaster& operator=(const TempRaster&) = delete;

  // Rows [y0, y0 + n) from `data`: pixels `pixel_bytes` apart, bands
  // byte-interleaved within a pixel (packed RGBA: band k is byte k).
  void write(int y0, int n, const void* data, int pixel_bytes) {
    detail::GdalErrorCapture capture;
    if (GDALDatasetRasterIO(ds_, GF_Write, 0, y0, w_, n, const_cast<void*>(data), w_, n, type_,
                            bands_, nullptr, pixel_bytes, GSpacing(w_) * pixel_bytes,
                            bands_ > 1 ? 1 : 0) != CE_None)
      throw InputError(
          fmt::format("{}: cannot write rows {}..{}: {}", path_, y0, y0 + n - 1, capture.last()));
  }
  void close() {
    if (ds_) GDALClose(ds_);
    ds_ = nullptr;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int w_;
  GDALDataType type_;
  int bands_;
  GDALDatasetH ds_ = nullptr;
};

// Rows of one raster gathered into bands of `rows` before they are written.
template <class T>
class RowBand {
 public:
  RowBand(TempRaster& file, int w, int rows, int pixel_bytes)
      : file_(&file), w_(w), rows_(rows), pixel_bytes_(pixel_bytes), data_(std::size_t(w) * rows) {}
  T* next_row() { return slot(0); }
  T* slot(int k) { return data_.data() + std::size_t(n_ + k) * w_; }
  void commit_row() {
    if (++n_ == rows_) flush();
  }
  void flush() {
    if (n_ > 0) file_->write(y0_, n_, data_.data(), pixel_bytes_);
    y0_ += n_;
    n_ = 0;
  }
  int rows_done() const { return y0_ + n_; }

 private:
  TempRaster* file_;
  int w_, rows_, pixel_bytes_;
  std::vector<T> data_;
  int y0_ = 0, n_ = 0;
};

// One render level: the finer level's last three rows, this level's rows
// on their way to its files.
struct RenderLevel {
  int w = 0, h = 0;
  std::array<std::vector<float>, 3> fh;  // finer rows, row r at r % 3
  std::array<std::vector<std::uint32_t>, 3> fc;
  int next = 0;  // the next row of this level to emit
  std::unique_ptr<TempRaster> hfile, cfile;
  std::unique_ptr<RowBand<float>> hband;
  std::unique_ptr<RowBand<std::uint32_t>> cband;
};

// One bound level: its last three cell rows (max over each cell's samples),
// its bound rows (dilated by one cell) on their way to its file, and the
// highest bound of each tile.
struct BoundRows {
  int w = 0, h = 0;                         // cells
  std::array<std::vector<float>, 3> cells;  // cell row b at b % 3
  std::vector<float> coarser;               // the coarser level's cell row being made
  int next = 0;                             // the next bound row to emit
  int tiles_x = 0;
  std::vector<float> tile_max;
  std::unique_ptr<TempRaster> file;
  std::unique_ptr<RowBand<float>> band;
};

class PyramidStrips {
 public:
  PyramidStrips(const TerrainRows& rows, const std::string& tmp, int tile_log2, int band_rows)
      : tile_log2_(tile_log2) {
    const int T = 1 << tile_log2;
    // Render levels: VoxelTerrain's rule, halving while the longer side has
    // more than one cell and the size still changes.
    for (int L = 0; L < 30; ++L) {
      const int w = TerrainGrid::level_size(rows.width, L),
                h = TerrainGrid::level_size(rows.height, L);
      if (L > 0 && (std::max(w, h) <= 2 || (w == levels_.back().w && h == levels_.back().h))) break;
      RenderLevel& l = levels_.emplace_back();
      l.w = w;
      l.h = h;
      l.hfile = std::make_unique<TempRaster>(fmt::format("{}/height_{}.tif", tmp, L), w, h,
                                             GDT_Float32, 1, T);
      l.cfile = std::make_unique<TempRaster>(fmt::format("{}/color_{}.tif", tmp, L), w, h, GDT_Byte,
                                             3, T);
      const int rows_at_once = L == 0 ? band_rows : T;
      l.hband = std::make_unique<RowBand<float>>(*l.hfile, w, rows_at_once, 4);
      l.cband = std::make_unique<RowBand<std::uint32_t>>(*l.cfile, w, rows_at_once, 4);
      if (L > 0) {
        const RenderLevel& f = levels_[levels_.size() - 2];
        for (auto& r : l.fh) r.resize(std::size_t(f.w));
        for (auto& r : l.fc) r.resize(std::size_t(f.w));
      }
    }
    // Bound levels: cells of level 0, halved (rounding up) down to 1 x 1.
    int cw = std::max(1, rows.width - 1), ch = std::max(1, rows.height - 1);
    for (int k = 0;; ++k) {
      if (k > 0) {
        cw = (cw + 1) / 2;
        ch = (ch + 1) / 2;
      }
      BoundRows& b = bounds_.emplace_back();
      b.w = cw;
      b.h = ch;
      for (auto& r : b.cells) r.resize(std::size_t(cw));
      b.tiles_x = (cw + T - 1) / T;
      b.tile_max.assign(std::size_t(b.tiles_x) * ((ch + T - 1) / T),
                        -std::numeric_limits<float>::infinity());
      b.file = std::make_unique<TempRaster>(fmt::format("{}/bound_{}.tif", tmp, k), cw, ch,
                                            GDT_Float32, 1, T);
      b.band = std::make_unique<RowBand<float>>(*b.file, cw, T, 4);
      if (cw == 1 && ch == 1) break;
    }
    for (std::size_t k = 0; k + 1 < bounds_.size(); ++k)
      bounds_[k].coarser.resize(std::size_t(bounds_[k + 1].w));
    prev0_.resize(std::size_t(rows.width));
  }

  // Level-0 rows k = 0, 1, ... past the last committed one, in the band's
  // storage (k < band_rows when bands start at multiples of band_rows);
  // committed in order.
  float* level0_heights(int k) { return levels_[0].hband->slot(k); }
  std::uint32_t* level0_colors(int k) { return levels_[0].cband->slot(k); }
  void commit_level0_row() { commit_row(0); }

  // Flushes every band and closes the files; checks every row was made.
  void finish() {
    for (RenderLevel& l : levels_) {
      l.hband->flush();
      l.cband->flush();
      if (l.hband->rows_done() != l.h) throw std::logic_error("strip pyramid: rows missing");
      l.hfile->close();
      l.cfile->close();
    }
    for (BoundRows& b : bounds_) {
      b.band->flush();
      if (b.band->rows_done() != b.h) throw std::logic_error("strip pyramid: bound rows missing");
      b.file->close();
    }
  }

  int coarsest_level() const { return int(levels_.size()) - 1; }
  int bound_levels() const { return int(bounds_.size()); }
  std::vector<LevelSource> sources(const char* kind) const {
    std::vector<LevelSource> out;
    if (std::string(kind) == "bound") {
      for (const BoundRows& b : bounds_) out.push_back({b.file->path(), b.w, b.h});
    } else {
      for (const RenderLevel& l : levels_)
        out.push_back(
            {std::string(kind) == "height" ? l.hfile->path() : l.cfile->path(), l.w, l.h});
    }
    return out;
  }
  std::vector<std::vector<float>> tile_max() const {
    std::vector<std::vector<float>> out;
    for (const BoundRows& b : bounds_) out.push_back(b.tile_max);
    return out;
  }

 private:
  // The row just written into level L's bands is complete: hand it on.
  void commit_row(int L) {
    RenderLevel& l = levels_[std::size_t(L)];
    const int j = l.next++;
    const float* h = l.hband->next_row();
    const std::uint32_t* c = l.cband->next_row();
    if (L == 0) level0_cells(j, h);
    if (std::size_t(L) + 1 < levels_.size()) push_finer(L + 1, j, h, c);
    l.hband->commit_row();
    l.cband->commit_row();
  }

  // Finer row r of level L arrives: emit every row of L it completes.
  void push_finer(int L, int r, const float* h, const std::uint32_t* c) {
    RenderLevel& l = levels_[std::size_t(L)];
    const int fw = levels_[std::size_t(L) - 1].w, fh = levels_[std::size_t(L) - 1].h;
    std::copy(h, h + fw, l.fh[std::size_t(r % 3)].begin());
    std::copy(c, c + fw, l.fc[std::size_t(r % 3)].begin());
    while (l.next < l.h && std::min(2 * l.next + 1, fh - 1) <= r) {
      const int j = l.next;
      const float* rh[3];
      const std::uint32_t* rc[3];
      for (int b = 0; b < 3; ++b) {
        const int fj = std::clamp(2 * j + b - 1, 0, fh - 1);
        rh[b] = l.fh[std::size_t(fj % 3)].data();
        rc[b] = l.fc[std::size_t(fj % 3)].data();
      }
      float* oh = l.hband->next_row();
      std::uint32_t* oc = l.cband->next_row();
      for_columns(l.w, [&](int i0, int i1) { halve_row(rh, rc, fw, i0, i1, oh, oc); });
      commit_row(L);
    }
  }

  // Level-0 sample row j arrives: cell row j - 1 is the max of rows j - 1, j.
  void level0_cells(int j, const float* h) {
    const int w = levels_[0].w;
    if (j > 0) {
      BoundRows& b0 = bounds_[0];
      float* cells = b0.cells[std::size_t((j - 1) % 3)].data();
      for_columns(b0.w, [&](int a0, int a1) {
        for (int a = a0; a < a1; ++a)
          cells[a] = std::max(std::max(prev0_[std::size_t(a)], prev0_[std::size_t(a) + 1]),
                              std::max(h[a], h[a + 1]));
      });
      push_cells(0, j - 1);
    }
    std::copy(h, h + w, prev0_.begin());
  }

  // Cell row b of bound level k is in its ring: emit the bound rows it
  // completes, and the coarser cell row when it completes one.
  void push_cells(int k, int b) {
    BoundRows& bl = bounds_[std::size_t(k)];
    const int T = 1 << tile_log2_;
    while (bl.next < bl.h && std::min(bl.next + 1, bl.h - 1) <= b) {
      const int e = bl.next++;
      float* out = bl.band->next_row();
      const int y0 = std::max(e - 1, 0), y1 = std::min(e + 1, bl.h - 1);
      for_columns(bl.w, [&](int a0, int a1) {
        for (int a = a0; a < a1; ++a) {
          float m = -std::numeric_limits<float>::infinity();
          for (int y = y0; y <= y1; ++y) {
            const float* r = bl.cells[std::size_t(y % 3)].data();
            for (int x = std::max(a - 1, 0); x <= std::min(a + 1, bl.w - 1); ++x)
              m = std::max(m, r[x]);
          }
          out[a] = m;
        }
      });
      float* tm = bl.tile_max.data() + std::size_t(e / T) * std::size_t(bl.tiles_x);
      for (int a = 0; a < bl.w; ++a) tm[a / T] = std::max(tm[a / T], out[a]);
      bl.band->commit_row();
    }
    if (std::size_t(k) + 1 < bounds_.size() && (b % 2 == 1 || b == bl.h - 1)) {
      BoundRows& cl = bounds_[std::size_t(k) + 1];
      const float* r0 = bl.cells[std::size_t((b & ~1) % 3)].data();
      const float* r1 = bl.cells[std::size_t(b % 3)].data();
      float* out = cl.cells[std::size_t((b / 2) % 3)].data();
      for_columns(cl.w, [&](int a0, int a1) {
        for (int a = a0; a < a1; ++a) {
          const int x0 = 2 * a, x1 = std::min(2 * a + 1, bl.w - 1);
          out[a] = std::max(std::max(r0[x0], r0[x1]), std::max(r1[x0], r1[x1]));
        }
      });
      push_cells(k + 1, b / 2);
    }
  }

  int tile_log2_;
  std::vector<RenderLevel> levels_;
  std::vector<BoundRows> bounds_;
  std::vector<float> prev0_;  // level-0 row j - 1
};

// Removes the temporary directory however the writer ends.
struct TempDir {
  fs::path path;
  explicit TempDir(fs::path p) : path(std::move(p)) {
    std::error_code ec;
    fs::remove_all(path, ec);
    if (!fs::create_directories(path, ec) || ec)
      throw InputError(fmt::format("{}: cannot create: {}", path.string(), ec.message()));
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  long long bytes() const {
    long long n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(path, ec))
      if (e.is_regular_file(ec)) n += static_cast<long long>(e.file_size(ec));
    return n;
  }
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TerrainRows terrain_rows(const LargeTerrain& t) {
  TerrainRows r;
  r.width = t.width;
  r.height = t.height;
  r.spacing_x = t.spacing_x;
  r.spacing_y = t.spacing_y;
  r.min_height = t.min_height;
  r.max_height = t.max_height;
  r.row = [&t](int j, float* heights, std::uint32_t* colors) {
    t.row(j, heights);
    drape_colour_row(t.texture, t.tex_rect, t.width, t.height, j, colors);
  };
  return r;
}

StripWriteStats write_tiled_terrain_strips(const TerrainRows& rows,
                                           const std::optional<GeoTransform>& geo,
                                           const std::string& dir, const TileWriteOptions& o,
                                           int band_rows) {
  check_write_options(o);
  if (o.fine || !o.insets.empty())
    throw InputError(fmt::format("{}: insets need the terrain in memory, not strips", dir));
  if (rows.width < 2 || rows.height < 2)
    throw InputError(fmt::format("{}: the terrain has no area to tile", dir));
  detail::ensure_gdal();
  StripWriteStats stats;
  const int T = 1 << o.tile_log2;
  // Level-0 rows made at once (in parallel): whole tile rows, about 64 MB.
  stats.band_rows =
      band_rows > 0 ? band_rows
                    : std::max(T, int(std::min<long long>(1024, (8LL << 20) / rows.width)) / T * T);
  if (stats.band_rows % T != 0)
    throw InputError(
        fmt::format("band_rows {}: must be a multiple of the tile size {}", stats.band_rows, T));
  const TempDir tmp(fs::path(dir) / ".strips");
  const auto t0 = std::chrono::steady_clock::now();
  PyramidStrips p(rows, tmp.path.string(), o.tile_log2, stats.band_rows);
  for (int j0 = 0; j0 < rows.height; j0 += stats.band_rows) {
    const int n = std::min(stats.band_rows, rows.height - j0);
    tbb::parallel_for(0, n,
                      [&](int k) { rows.row(j0 + k, p.level0_heights(k), p.level0_colors(k)); });
    for (int k = 0; k < n; ++k) p.commit_level0_row();
  }
  p.finish();
  stats.temp_bytes = tmp.bytes();
  stats.pyramid_s = seconds_since(t0);

  const auto t1 = std::chrono::steady_clock::now();
  write_level_cogs(p.sources("height"), p.sources("color"), p.sources("bound"), geo, dir, o);
  stats.cogs_s = seconds_since(t1);

  TerrainGrid g;
  g.width = rows.width;
  g.height = rows.height;
  g.spacing_x = rows.spacing_x;
  g.spacing_y = rows.spacing_y;
  g.min_height = rows.min_height;
  g.max_height = rows.max_height;
  g.finest_level = 0;
  g.coarsest_level = p.coarsest_level();
  g.bound_levels = p.bound_levels();
  g.tile_log2 = o.tile_log2;
  write_tile_set_json(g, p.tile_max(), geo, o, dir + "/tiles.json");
  return stats;
}

}  // namespace terrasprite
