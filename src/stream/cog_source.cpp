// SPDX-License-Identifier: MIT
// An existing COG as a tiled terrain. GDAL's overviews are area-aligned: pixel
// j of an overview reduced by f covers level-0 pixels [j f, (j + 1) f), its
// centre at level-0 index (j + 0.5) f - 0.5. The ray caster's levels are
// vertex-aligned (sample i of level L at level-0 index i 2^L), so each level
// reads the coarsest overview with f <= 2^L bilinearly at its pixel-centre
// coordinate; level 0 reads the raster itself (exactly). The max-height
// bounds cannot come from a smoothed level, so one pass over the raster and
// every overview (in strips) computes them at open.
#include "stream/cog_source.h"

#include <fmt/format.h>
#include <gdal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <thread>

#include "stream/cog_bounds_cache.h"
#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kStripRows = 256;
// Rasters from this many samples (2049²) cache their bounds by default (the
// pass takes seconds there); smaller ones only with TERRASPRITE_CACHE set.
constexpr std::int64_t kCacheSamples = std::int64_t(1) << 22;

struct Dataset {
  GDALDatasetH h = nullptr;
  explicit Dataset(const std::string& path) {
    detail::GdalErrorCapture capture;
    h = GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    if (!h) {
      std::error_code ec;
      const bool there = path.starts_with("/vsi") || std::filesystem::exists(path, ec);
      throw InputError(
          fmt::format("{}: {}", path, there ? "cannot open: " + capture.last() : "no such file"));
    }
  }
  ~Dataset() { GDALClose(h); }
  Dataset(const Dataset&) = delete;
  Dataset& operator=(const Dataset&) = delete;
};

GDALRasterBandH raster_band(GDALDatasetH ds, int b, int raster) {
  GDALRasterBandH band = GDALGetRasterBand(ds, b);
  return raster == 0 || !band ? band : GDALGetOverview(band, raster - 1);
}

std::vector<CogInput::Raster> rasters_of(GDALDatasetH ds) {
  GDALRasterBandH b = GDALGetRasterBand(ds, 1);
  std::vector<CogInput::Raster> r{{GDALGetRasterXSize(ds), GDALGetRasterYSize(ds)}};
  for (int k = 0; k < GDALGetOverviewCount(b); ++k) {
    GDALRasterBandH o = GDALGetOverview(b, k);
    r.push_back({GDALGetRasterBandXSize(o), GDALGetRasterBandYSize(o)});
  }
  return r;
}

int cells_of(int n0, int level) {
  return int((std::int64_t(std::max(1, n0 - 1)) + (std::int64_t(1) << level) - 1) >> level);
}

// Max of each cell and its neighbours (the bound of TileBlock).
std::vector<float> dilate(const std::vector<float>& cells, int cw, int ch) {
  std::vector<float> out(cells.size());
  for (int b = 0; b < ch; ++b)
    for (int a = 0; a < cw; ++a) {
      float m = -kInf;
      for (int y = std::max(b - 1, 0); y <= std::min(b + 1, ch - 1); ++y)
        for (int x = std::max(a - 1, 0); x <= std::min(a + 1, cw - 1); ++x)
          m = std::max(m, cells[std::size_t(y) * cw + x]);
      out[std::size_t(b) * cw + a] = m;
    }
  return out;
}

std::vector<float> halve_max(const std::vector<float>& cells, int cw, int ch, int nw, int nh) {
  std::vector<float> out(std::size_t(nw) * nh, -kInf);
  for (int y = 0; y < ch; ++y)
    for (int x = 0; x < cw; ++x) {
      float& m = out[std::size_t(y / 2) * nw + x / 2];
      m = std::max(m, cells[std::size_t(y) * cw + x]);
    }
  return out;
}

// The pass at open: every level-0 sample and every overview pixel is folded
// into the undilated max of the bound_from cell holding it (level-0 samples:
// every cell they are a corner of; overview pixels: the cell under their
// centre). A level-L' sample interpolates overview pixels within 2^L' of it,
// so the dilated bound of level L >= L' + 2 covers it, as TileBlock requires,
// whatever filter made the overviews (cubic overshoot included).
void compute_bounds(TileSetInfo& set, CogInput& in, bool has_nodata, double nodata,
                    long long held_cells) {
  const auto t0 = std::chrono::steady_clock::now();
  // GDAL's default block cache (5% of RAM) would keep the whole pass
  // resident: a strip of blocks is all it needs.
  if (GDALGetCacheMax64() > (GIntBig(64) << 20)) GDALSetCacheMax64(GIntBig(64) << 20);
  const int W = set.grid.width, H = set.grid.height;
  const int cw0 = set.tiles_cells_w(0), ch0 = set.tiles_cells_h(0);
  int Lb = 0;
  while (std::int64_t(cells_of(W, Lb)) * cells_of(H, Lb) > held_cells) ++Lb;
  Lb = std::min(Lb, set.grid.bound_levels - 1);
  const int cwb = cells_of(W, Lb), chb = cells_of(H, Lb);
  // A second open of the same unchanged file reads the pass's result back.
  bool explicit_dir = false;
  const std::string cache = bounds_cache_dir(explicit_dir);
  const bool use_cache = !cache.empty() && (explicit_dir || std::int64_t(W) * H >= kCacheSamples);
  const std::string key =
      use_cache ? bounds_cache_key(in, W, H, Lb, set.grid.bound_levels, has_nodata, nodata)
                : std::string();
  float cached_lo = 0, cached_hi = 0;
  if (use_cache &&
      load_cog_bounds(cache, key, W, H, Lb, set.grid.bound_levels, in, cached_lo, cached_hi)) {
    set.grid.min_height = cached_lo;
    set.grid.max_height = cached_hi;
    in.bounds_cached = true;
    in.bounds_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return;
  }
  auto cell_x = [&](long long x) { return int(std::clamp<long long>(x, 0, cw0 - 1) >> Lb); };
  auto cell_y = [&](long long y) { return int(std::clamp<long long>(y, 0, ch0 - 1) >> Lb); };
  // Strips of every raster, shared out to threads with a handle and a cell
  // array each (GDAL handles are not thread-safe); maxima merge at the end.
  struct Strip {
    int r, y0;
  };
  std::vector<Strip> strips;
  for (std::size_t r = 0; r < in.height_rasters.size(); ++r)
    for (int y0 = 0; y0 < in.height_rasters[r].h; y0 += kStripRows) strips.push_back({int(r), y0});
  struct Part {
    std::vector<float> cells;
    float lo = kInf, hi = -kInf;
    long long voids = 0;
    std::string error;
  };
  const int nt = int(std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 4));
  std::vector<Part> parts(static_cast<std::size_t>(nt));
  std::atomic<std::size_t> next{0};
  auto work = [&](Part& p) {
    p.cells.assign(std::size_t(cwb) * chb, -kInf);
    detail::GdalErrorCapture capture;
    GDALDatasetH h =
        GDALOpenEx(in.path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    if (!h) {
      p.error = fmt::format("{}: cannot open: {}", in.path, capture.last());
      return;
    }
    std::vector<float> strip;
    for (std::size_t k; p.error.empty() && (k = next.fetch_add(1)) < strips.size();) {
      const int r = strips[k].r, y0 = strips[k].y0;
      const int sw = in.height_rasters[std::size_t(r)].w, sh = in.height_rasters[std::size_t(r)].h;
      const double fx = double(W) / sw, fy = double(H) / sh;
      const int n = std::min(kStripRows, sh - y0);
      strip.resize(std::size_t(sw) * n);
      if (GDALRasterIO(raster_band(h, 1, r), GF_Read, 0, y0, sw, n, strip.data(), sw, n,
                       GDT_Float32, 0, 0) != CE_None) {
        p.error = fmt::format("{}: cannot read rows {}..{} of raster {}: {}", in.path, y0,
                              y0 + n - 1, r, capture.last());
        break;
      }
      for (int j = 0; j < n; ++j) {
        const float* row = strip.data() + std::size_t(j) * sw;
        const int y = y0 + j;
        if (r == 0) {
          const int b0 = cell_y(y - 1), b1 = cell_y(y);
          for (int x = 0; x < sw; ++x) {
            const float v = row[x];
            if (std::isnan(v) || (has_nodata && double(v) == nodata)) {
              ++p.voids;
              continue;
            }
            p.lo = std::min(p.lo, v);
            p.hi = std::max(p.hi, v);
            const int a0 = cell_x(x - 1), a1 = cell_x(x);
            for (int b : {b0, b1})
              for (int a : {a0, a1}) {
                float& m = p.cells[std::size_t(b) * cwb + a];
                m = std::max(m, v);
              }
          }
        } else {
          const int b = cell_y((long long)std::floor((y + 0.5) * fy - 0.5));
          for (int x = 0; x < sw; ++x) {
            if (std::isnan(row[x]) || (has_nodata && double(row[x]) == nodata)) continue;
            float& m =
                p.cells[std::size_t(b) * cwb + cell_x((long long)std::floor((x + 0.5) * fx - 0.5))];
            m = std::max(m, row[x]);
          }
        }
      }
    }
    GDALClose(h);
  };
  {
    std::vector<std::jthread> threads;
    for (int t = 1; t < nt; ++t) threads.emplace_back([&, t] { work(parts[std::size_t(t)]); });
    work(parts[0]);
  }
  std::vector<float> cells = std::move(parts[0].cells);
  float lo = kInf, hi = -kInf;
  long long voids = 0;
  for (Part& p : parts) {
    if (!p.error.empty()) throw InputError(p.error);
    lo = std::min(lo, p.lo);
    hi = std::max(hi, p.hi);
    voids += p.voids;
    if (&p != &parts[0])
      for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = std::max(cells[i], p.cells[i]);
  }
  if (voids > 0)
    throw InputError(fmt::format(
        "{}: {} nodata samples; fill the voids first (terrasprite tile --dem {} fills them)",
        in.path, voids, in.path));
  set.grid.min_height = lo;
  set.grid.max_height = hi;
  in.bound_from = Lb;
  int cw = cwb, ch = chb;
  for (int L = Lb; L < set.grid.bound_levels; ++L) {
    if (L > Lb) {
      const int nw = cells_of(W, L), nh = cells_of(H, L);
      cells = halve_max(cells, cw, ch, nw, nh);
      cw = nw;
      ch = nh;
    }
    in.bound.push_back(dilate(cells, cw, ch));
  }
  if (use_cache) save_cog_bounds(cache, key, in, lo, hi);
  in.bounds_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Cell (a, b) of `level`'s bound: held, or the held bound_from cell holding it.
float bound_at(const TileSetInfo& set, const CogInput& in, int level, int a, int b) {
  const int Lb = in.bound_from;
  if (level >= Lb) {
    return in.bound[std::size_t(level - Lb)][std::size_t(b) * set.tiles_cells_w(level) + a];
  }
  const int s = Lb - level;
  return in.bound[0][std::size_t(b >> s) * set.tiles_cells_w(Lb) + (a >> s)];
}

// a + (b - a) t, never outside [a, b] (a rounded-up mix would poke above
// the bounds), exactly a at t = 0.
float mix(float a, float b, float t) {
  return std::clamp(a + (b - a) * t, std::min(a, b), std::max(a, b));
}

// Level samples first.. (n of them) along an axis of n0 level-0 samples, as
// positions in a raster of ns pixels: pixel i0[k] and i0[k] + 1, weight t[k].
struct Axis {
  std::vector<int> i0;
  std::vector<float> t;
  int lo = 0, hi = 0;  // pixels read
};

Axis axis(int first, int n, int level, int n0, int ns) {
  Axis a;
  const double f = double(n0) / ns;
  for (int k = 0; k < n; ++k) {
    const double X = std::min(double(std::int64_t(first + k) << level), double(n0 - 1));
    const double u = std::clamp((X + 0.5) / f - 0.5, 0.0, double(ns - 1));
    const int i = std::min(int(std::floor(u)), std::max(ns - 2, 0));
    a.i0.push_back(i);
    a.t.push_back(float(u - i));
  }
  a.lo = a.i0.front();
  a.hi = std::min(a.i0.back() + 1, ns - 1);
  return a;
}

}  // namespace

int cog_raster_for_level(const std::vector<CogInput::Raster>& rasters, int level) {
  const double limit = double(std::int64_t(1) << level) * 1.01;
  int best = 0;
  double best_f = 1.0;
  for (std::size_t k = 1; k < rasters.size(); ++k) {
    const double fx = double(rasters[0].w) / rasters[k].w, fy = double(rasters[0].h) / rasters[k].h;
    if (fx <= limit && fy <= limit && std::min(fx, fy) > best_f) {
      best = int(k);
      best_f = std::min(fx, fy);
    }
  }
  return best;
}

bool read_cog_window(const TileSetInfo& set, GDALDatasetH height, GDALDatasetH texture, int level,
                     int x0, int y0, int w, int h, TileData& out, std::string& error) {
  const CogInput& in = *set.cog;
  detail::GdalErrorCapture capture;
  auto fail = [&](const char* what) {
    error = fmt::format("{} of level {} at ({}, {}): {}", what, level, x0, y0, capture.last());
    return false;
  };
  const std::size_t n = std::size_t(w) * h;
  out.height.clear();
  out.color.clear();
  if (level <= set.grid.coarsest_level) {
    // Reads `bands` bands of raster r of `ds` over the window's pixels as
    // floats, then interpolates each sample: `put(sample, band, value)`.
    std::vector<float> buf;
    auto resample = [&](GDALDatasetH ds, const std::vector<CogInput::Raster>& rs, int bands,
                        auto put) {
      const int r = cog_raster_for_level(rs, level);
      const Axis ax = axis(x0, w, level, set.grid.width, rs[std::size_t(r)].w);
      const Axis ay = axis(y0, h, level, set.grid.height, rs[std::size_t(r)].h);
      const int rw = ax.hi - ax.lo + 1, rh = ay.hi - ay.lo + 1;
      buf.resize(std::size_t(rw) * rh);
      for (int b = 0; b < bands; ++b) {
        GDALRasterBandH band = raster_band(ds, b + 1, r);
        if (!band || GDALRasterIO(band, GF_Read, ax.lo, ay.lo, rw, rh, buf.data(), rw, rh,
                                  GDT_Float32, 0, 0) != CE_None)
          return false;
        for (int j = 0; j < h; ++j) {
          const int y = ay.i0[std::size_t(j)] - ay.lo, y1 = std::min(y + 1, rh - 1);
          const float ty = ay.t[std::size_t(j)];
          for (int i = 0; i < w; ++i) {
            const int x = ax.i0[std::size_t(i)] - ax.lo, x1 = std::min(x + 1, rw - 1);
            const float tx = ax.t[std::size_t(i)];
            const float* r0 = buf.data() + std::size_t(y) * rw;
            const float* r1 = buf.data() + std::size_t(y1) * rw;
            put(std::size_t(j) * w + i, b, mix(mix(r0[x], r0[x1], tx), mix(r1[x], r1[x1], tx), ty));
          }
        }
      }
      return true;
    };
    out.height.resize(n);
    if (!resample(height, in.height_rasters, 1,
                  [&](std::size_t k, int, float v) { out.height[k] = v; }))
      return fail("height");
    out.color.assign(n, 0xff808080u);  // grey without a texture
    if (texture) {
      auto* bytes = reinterpret_cast<std::uint8_t*>(out.color.data());
      if (!resample(texture, in.texture_rasters, 3, [&](std::size_t k, int b, float v) {
            bytes[k * 4 + std::size_t(b)] = std::uint8_t(std::clamp(v + 0.5f, 0.f, 255.f));
          }))
        return fail("colour");
    }
  }
  const int cw = std::max(1, w - 1), ch = std::max(1, h - 1);
  out.bound.resize(std::size_t(cw) * ch);
  for (int b = 0; b < ch; ++b)
    for (int a = 0; a < cw; ++a)
      out.bound[std::size_t(b) * cw + a] = bound_at(set, in, level, x0 + a, y0 + b);
  return true;
}

TileSetInfo open_cog(const std::string& path, const std::string& texture, int tile_log2,
                     long long held_bound_cells) {
  detail::ensure_gdal();
  auto in = std::make_shared<CogInput>();
  in->path = path;
  in->texture = texture;
  TileSetInfo set;
  set.dir = path;
  Dataset ds(path);
  const int W = GDALGetRasterXSize(ds.h), H = GDALGetRasterYSize(ds.h);
  if (GDALGetRasterCount(ds.h) != 1)
    throw InputError(
        fmt::format("{}: {} bands; a height COG has exactly one", path, GDALGetRasterCount(ds.h)));
  GDALRasterBandH band = GDALGetRasterBand(ds.h, 1);
  int bx = 0, by = 0;
  GDALGetBlockSize(band, &bx, &by);
  if (!(bx < W || (bx == by && by > 1)))
    throw InputError(fmt::format(
        "{}: not tiled (blocks of {}x{}); write it with gdal_translate -of COG {} out.tif", path,
        bx, by, path));
  if (GDALGetOverviewCount(band) < 1)
    throw InputError(fmt::format(
        "{}: no overviews; write it with gdal_translate -of COG {} out.tif (or gdaladdo)", path,
        path));
  if (W < 2 || H < 2) throw InputError(fmt::format("{}: {}x{} samples is too small", path, W, H));
  in->height_rasters = rasters_of(ds.h);
  TerrainGrid& g = set.grid;
  g.width = W;
  g.height = H;
  g.spacing_x = g.spacing_y = 30.0;
  double gt[6];
  if (GDALGetGeoTransform(ds.h, gt) == CE_None) {
    if (gt[2] != 0 || gt[4] != 0 || gt[1] < 0 || gt[5] > 0)
      throw InputError(
          fmt::format("{}: not north-up; warp it first (gdalwarp {} north_up.tif)", path, path));
    GeoTransform geo;
    if (detail::spacing_from_geo(ds.h, gt, W, H, g.spacing_x, g.spacing_y, geo)) set.geo = geo;
  }
  if (!set.geo)
    fmt::print(stderr, "terrasprite: warning: {}: no georeferencing; assuming 30 m spacing\n",
               path);
  check_spacing(path, g.spacing_x, g.spacing_y);
  int has_nodata = 0;
  const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
  if (!texture.empty()) {
    Dataset tex(texture);
    if (GDALGetRasterCount(tex.h) < 3 || GDALGetRasterXSize(tex.h) != W ||
        GDALGetRasterYSize(tex.h) != H)
      throw InputError(
          fmt::format("{}: {}x{} with {} bands; the texture must be RGB of {}x{} like {}", texture,
                      GDALGetRasterXSize(tex.h), GDALGetRasterYSize(tex.h),
                      GDALGetRasterCount(tex.h), W, H, path));
    in->texture_rasters = rasters_of(tex.h);
  }
  // Levels as VoxelTerrain has them: halve while a side has more than 2 samples.
  g.finest_level = 0;
  g.coarsest_level = 0;
  for (int L = 1; L < 30; ++L) {
    const int w = g.level_width(L), h = g.level_height(L);
    if (std::max(w, h) <= 2 || (w == g.level_width(L - 1) && h == g.level_height(L - 1))) break;
    g.coarsest_level = L;
  }
  g.bound_levels = 1;
  while (cells_of(W, g.bound_levels - 1) > 1 || cells_of(H, g.bound_levels - 1) > 1)
    ++g.bound_levels;
  if (tile_log2 <= 0) {  // one tile of level 0 = one block of the COG, when its blocks are square
    tile_log2 = 7;
    for (int k = 4; k <= 9; ++k)
      if (bx == by && bx == 1 << k) tile_log2 = k;
  }
  g.tile_log2 = tile_log2;
  compute_bounds(set, *in, has_nodata != 0, nodata, std::max(1LL, held_bound_cells));
  check_height_range(path, g.min_height, g.max_height,
                     "tag its nodata value (gdal_edit.py -a_nodata) or fix its scale");
  const int T = 1 << tile_log2;
  for (int L = 0; L < g.bound_levels; ++L) {
    const int cw = set.tiles_cells_w(L), ch = set.tiles_cells_h(L);
    const int nx = (cw + T - 1) / T, ny = (ch + T - 1) / T;
    set.tiles_x.push_back(nx);
    set.tiles_y.push_back(ny);
    auto& maxes = set.tile_max.emplace_back(std::size_t(nx) * ny, -kInf);
    // Finer than bound_from, a tile's cells repeat the held cells holding them.
    const int s = std::max(0, in->bound_from - L), Lh = L + s;
    for (int ty = 0; ty < ny; ++ty)
      for (int tx = 0; tx < nx; ++tx) {
        float& m = maxes[std::size_t(ty) * nx + tx];
        for (int b = (ty * T) >> s; b <= (std::min(ch, (ty + 1) * T) - 1) >> s; ++b)
          for (int a = (tx * T) >> s; a <= (std::min(cw, (tx + 1) * T) - 1) >> s; ++a)
            m = std::max(m, bound_at(set, *in, Lh, a, b));
      }
  }
  std::error_code ec;
  set.bytes_on_disk = (long long)std::filesystem::file_size(path, ec);
  if (!texture.empty()) set.bytes_on_disk += (long long)std::filesystem::file_size(texture, ec);
  set.cog = std::move(in);
  return set;
}

TileSetInfo open_tile_source(const std::string& tiles, const std::string& cog,
                             const std::string& texture) {
  if (!tiles.empty() && !cog.empty()) throw InputError("--tiles and --cog: give one of the two");
  if (!cog.empty()) return open_cog(cog, texture);
  if (!texture.empty()) throw InputError(fmt::format("--texture {}: only with --cog", texture));
  if (tiles.empty())
    throw InputError(
        "--tiles DIR or --cog FILE: required (a directory written by terrasprite tile, or a COG)");
  return read_tile_set(tiles);
}

}  // namespace terrasprite
