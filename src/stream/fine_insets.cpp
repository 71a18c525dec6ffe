// SPDX-License-Identifier: MIT
#include "terrasprite/stream/fine_insets.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "stream/inset_warp.h"
#include "terrasprite/common/error.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite {
namespace {

// Bilinear sample of a row-major w x h float grid at (x, y), clamped.
float bilinear(const std::vector<float>& p, int w, int h, double x, double y) {
  x = std::clamp(x, 0.0, double(w - 1));
  y = std::clamp(y, 0.0, double(h - 1));
  const int i = std::min(int(x), std::max(w - 2, 0)), j = std::min(int(y), std::max(h - 2, 0));
  const int i1 = std::min(i + 1, w - 1), j1 = std::min(j + 1, h - 1);
  const float fx = float(x - i), fy = float(y - j);
  auto at = [&](int a, int b) { return p[std::size_t(b) * w + a]; };
  const float top = at(i, j) + (at(i1, j) - at(i, j)) * fx;
  const float bot = at(i, j1) + (at(i1, j1) - at(i, j1)) * fx;
  return top + (bot - top) * fy;
}

// The base's colour at base sample (x, y) (fractional), through its texture mapping.
void base_color(const Terrain& t, double x, double y, float out[3]) {
  const Image& tex = t.texture;
  if (tex.empty()) {
    out[0] = out[1] = out[2] = 128.f;
    return;
  }
  const Heightfield& hf = t.heights;
  const auto& r = t.tex_rect;
  const double s = hf.width > 1 ? x / (hf.width - 1) : 0.5,
               q = hf.height > 1 ? y / (hf.height - 1) : 0.5;
  const double cx = std::clamp((r[0] + s * r[2]) * tex.width - 0.5, 0.0, double(tex.width - 1));
  const double cy = std::clamp((r[1] + q * r[3]) * tex.height - 0.5, 0.0, double(tex.height - 1));
  const int i = std::min(int(cx), std::max(tex.width - 2, 0)),
            j = std::min(int(cy), std::max(tex.height - 2, 0));
  const int i1 = std::min(i + 1, tex.width - 1), j1 = std::min(j + 1, tex.height - 1);
  const float fx = float(cx - i), fy = float(cy - j);
  for (int c = 0; c < 3; ++c) {
    const float top = tex.px(i, j)[c] + (tex.px(i1, j)[c] - tex.px(i, j)[c]) * fx;
    const float bot = tex.px(i, j1)[c] + (tex.px(i1, j1)[c] - tex.px(i, j1)[c]) * fx;
    out[c] = top + (bot - top) * fy;
  }
}

}  // namespace

FineWindow build_fine_window(const Terrain& base, const GridGeo& g,
                             const std::vector<InsetSpec>& insets, int levels, int tile_log2) {
  if (levels < 1 || levels > 8)
    throw InputError(fmt::format("--fine-levels {}: must be 1..8", levels));
  const Heightfield& hf = base.heights;
  const int s = 1 << levels;
  const long long align = (1LL << tile_log2) << (levels - 1);
  const long long fw = (long long)(hf.width - 1) * s + 1, fh = (long long)(hf.height - 1) * s + 1;
  // Warp each inset once; the window spans their pixel centres, origin aligned.
  std::vector<detail::Warped> warped;
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  for (const InsetSpec& spec : insets) {
    detail::Warped r = detail::warp(spec, g.wkt);
    for (double px : {0.5, r.w - 0.5})
      for (double py : {0.5, r.h - 0.5}) {
        const double X = r.gt[0] + px * r.gt[1], Y = r.gt[3] + py * r.gt[5];
        const double u = (X - g.x0) / g.dx * s, v = (g.y0 - Y) / g.dy * s;
        u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
      }
    warped.push_back(std::move(r));
  }
  FineWindow win;
  win.levels = levels;
  const long long x0 = std::clamp((long long)std::floor(u0) / align * align, 0LL, fw - 1);
  const long long y0 = std::clamp((long long)std::floor(v0) / align * align, 0LL, fh - 1);
  // Whole tiles at every fine level (or up to the grid's edge): a tile of the
  // window is then the combined grid's tile of the same cells.
  auto end = [&](double hi, long long lo, long long n) {
    const long long e = std::max((long long)std::ceil(hi) + 1, lo + 1);
    return std::clamp(lo + (e - lo + align - 1) / align * align, 0LL, n - 1);
  };
  const long long x1 = end(u1, x0, fw), y1 = end(v1, y0, fh);
  if (x1 - x0 < 1 || y1 - y0 < 1)
    throw InputError(fmt::format("{}: covers no sample of the base terrain (after reprojection)",
                                 insets.empty() ? "--inset" : insets[0].path));
  const long long w = x1 - x0 + 1, h = y1 - y0 + 1;
  if (w * h > (1LL << 30))
    throw InputError(
        fmt::format("--fine-levels {}: the insets' window would be {} x {} samples "
                    "(over 2^30); use fewer fine levels",
                    levels, w, h));
  win.origin_x = int(x0);
  win.origin_y = int(y0);
  // The base upsampled, then the insets over it.
  Heightfield& f = win.terrain.heights;
  f.width = int(w);
  f.height = int(h);
  f.spacing_x = hf.spacing_x / s;
  f.spacing_y = hf.spacing_y / s;
  f.name = hf.name + " (fine)";
  f.heights.resize(std::size_t(w * h));
  for (long long j = 0; j < h; ++j)
    for (long long i = 0; i < w; ++i)
      f.heights[std::size_t(j * w + i)] =
          bilinear(hf.heights, hf.width, hf.height, double(x0 + i) / s, double(y0 + j) / s);
  const std::vector<float> up = f.heights;
  win.weight.assign(f.heights.size(), 0.f);
  GridGeo fg = g;
  fg.dx = g.dx / s;
  fg.dy = g.dy / s;
  fg.x0 = g.x0 + double(x0) * fg.dx;
  fg.y0 = g.y0 - double(y0) * fg.dy;
  for (std::size_t k = 0; k < insets.size(); ++k) {
    InsetResult res = detail::composite_warped(f, fg, insets[k], warped[k], &win.weight);
    if (res.samples_replaced == 0)
      throw InputError(fmt::format("{}: covers no sample of the fine levels", insets[k].path));
    win.results.push_back(res);
  }
  warped.clear();
  // Colour: the base's upsampled, shaded by the insets' detail (lit from the
  // north-west) so a photo texture still shows the finer relief.
  Image& tex = win.terrain.texture;
  tex = Image(int(w), int(h));
  const double sx = 2 * f.spacing_x, sy = 2 * f.spacing_y;
  for (long long j = 0; j < h; ++j)
    for (long long i = 0; i < w; ++i) {
      float c[3];
      base_color(base, double(x0 + i) / s, double(y0 + j) / s, c);
      auto d = [&](long long a, long long b) {
        a = std::clamp(a, 0LL, w - 1);
        b = std::clamp(b, 0LL, h - 1);
        return double(f.heights[std::size_t(b * w + a)] - up[std::size_t(b * w + a)]);
      };
      const double gx = (d(i + 1, j) - d(i - 1, j)) / sx, gy = (d(i, j + 1) - d(i, j - 1)) / sy;
      const float shade = float(std::clamp(1.0 - 0.7 * (gx - gy), 0.5, 1.5));
      std::uint8_t* p = tex.px(int(i), int(j));
      for (int ch = 0; ch < 3; ++ch)
        p[ch] = std::uint8_t(std::clamp(c[ch] * shade + 0.5f, 0.f, 255.f));
      p[3] = 255;
    }
  // Window sample i on texel centre i.
  win.terrain.tex_rect = {0.5 / double(w), 0.5 / double(h), double(w - 1) / double(w),
                          double(h - 1) / double(h)};
  win.terrain.texture_name = "base, upsampled, shaded by the insets' detail";
  return win;
}

FineLevelsInfo fine_levels_info(const FineWindow& win, int base_w, int base_h, int tile_log2) {
  FineLevelsInfo fi;
  fi.levels = win.levels;
  fi.origin_x = win.origin_x;
  fi.origin_y = win.origin_y;
  const Heightfield& f = win.terrain.heights;
  const int T = 1 << tile_log2, s = 1 << win.levels;
  for (int l = 0; l < win.levels; ++l) {
    const int lw = TerrainGrid::level_size(f.width, l), lh = TerrainGrid::level_size(f.height, l);
    const int nx = (lw - 1 + T - 1) / T, ny = (lh - 1 + T - 1) / T;
    auto& p = fi.present.emplace_back(std::size_t(nx) * ny, 0);
    // A sample with inset weight reaches level-l samples within one of its
    // own (the tent filters' reach); mark every tile holding one of those.
    for (int j = 0; j < f.height; ++j)
      for (int i = 0; i < f.width; ++i) {
        if (win.weight[std::size_t(j) * f.width + i] <= 0.f) continue;
        const int a0 = std::max(0, (i >> l) - 1), a1 = std::min(lw - 1, (i >> l) + 2);
        const int b0 = std::max(0, (j >> l) - 1), b1 = std::min(lh - 1, (j >> l) + 2);
        for (int ty = std::max(0, (b0 - 1) / T); ty <= std::min(ny - 1, b1 / T); ++ty)
          for (int tx = std::max(0, (a0 - 1) / T); tx <= std::min(nx - 1, a1 / T); ++tx)
            p[std::size_t(ty) * nx + tx] = 1;
      }
  }
  // The highest window sample in each base level-0 cell it touches.
  const int cw = base_w - 1, ch = base_h - 1;
  fi.base_cell_max.assign(std::size_t(cw) * ch, -std::numeric_limits<float>::infinity());
  for (int j = 0; j < f.height; ++j)
    for (int i = 0; i < f.width; ++i) {
      const int gx = win.origin_x + i, gy = win.origin_y + j;
      const float v = f.heights[std::size_t(j) * f.width + i];
      const int a = gx / s, b = gy / s;
      for (int bb = (gy % s == 0 ? b - 1 : b); bb <= b; ++bb)
        for (int aa = (gx % s == 0 ? a - 1 : a); aa <= a; ++aa)
          if (aa >= 0 && bb >= 0 && aa < cw && bb < ch) {
            float& m = fi.base_cell_max[std::size_t(bb) * cw + aa];
            m = std::max(m, v);
          }
    }
  return fi;
}

FineLevelsInfo write_fine_insets(const Terrain& base, const GridGeo& grid,
                                 const std::vector<InsetSpec>& insets, int levels,
                                 const TileWriteOptions& options, const std::string& dir) {
  FineLevelsInfo fi;
  std::optional<GeoTransform> geo;
  {
    FineWindow win = build_fine_window(base, grid, insets, levels, options.tile_log2);
    for (const InsetResult& r : win.results)
      fmt::print(
          "{}: {} fine samples from the inset ({} at full weight), {} x {} window at {:.4g} m\n",
          r.path, r.samples_replaced, r.samples_full, win.terrain.heights.width,
          win.terrain.heights.height, win.terrain.heights.spacing_x);
    fi = fine_levels_info(win, base.heights.width, base.heights.height, options.tile_log2);
    const double fdx = grid.dx / (1 << levels), fdy = grid.dy / (1 << levels);
    GeoTransform gt;
    const double x = grid.x0 + win.origin_x * fdx, y = grid.y0 - win.origin_y * fdy;
    const double v[6] = {x - 0.5 * fdx, fdx, 0, y + 0.5 * fdy, 0, -fdy};
    std::copy(v, v + 6, gt.gt);
    gt.wkt = grid.wkt;
    geo = gt;
    const VoxelTerrain vt(win.terrain);
    win = FineWindow{};  // the pyramid holds what the files need
    std::filesystem::create_directories(dir + "/fine");
    TileWriteOptions o = options;
    o.insets.clear();
    o.fine.reset();
    write_tiled_terrain(vt, geo, dir + "/fine", o);
  }
  return fi;
}

}  // namespace terrasprite
