// SPDX-License-Identifier: MIT
// The ray caster's terrain pyramids (Cohen-Or et al., section on the
// multiresolution traversal): level L halves level L-1 with a [1 2 1]/4 tent,
// heights and colours alike; a max pyramid over cells bounds the surface for
// hierarchical empty-space skipping.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "terrasprite/common/error.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {
namespace {

int level_size(int n0, int level) {
  return TerrainGrid::level_size(n0, level);
}

constexpr int kTileLog2 = 7;

// Tile tables viewing the pyramids in place (see TerrainTiles).
void build_tiles(VoxelTerrain::Data& d) {
  TerrainGrid& g = d.grid;
  g.width = d.w;
  g.height = d.h;
  g.spacing_x = d.sx;
  g.spacing_y = d.sy;
  g.min_height = d.hmin;
  g.max_height = d.hmax;
  g.finest_level = 0;
  g.coarsest_level = int(d.levels.size()) - 1;
  g.bound_levels = int(d.maxes.size());
  g.tile_log2 = kTileLog2;
  constexpr int T = 1 << kTileLog2;
  d.tiles.resize(d.maxes.size());
  for (int L = 0; L < g.bound_levels; ++L) {
    const MaxLevel& ml = d.maxes[L];  // cells of level L
    const PyramidLevel* lev = L < int(d.levels.size()) ? &d.levels[L] : nullptr;
    auto& lt = d.tiles[L];
    lt.nx = (ml.w + T - 1) / T;
    lt.ny = (ml.h + T - 1) / T;
    lt.tiles.resize(std::size_t(lt.nx) * lt.ny);
    TileBlock& all = lt.whole;
    all.max_height = -std::numeric_limits<float>::infinity();
    all.w = ml.w + 1;
    all.h = ml.h + 1;
    all.bound = ml.bound.data();
    all.bound_stride = ml.w;
    if (lev) {
      all.height = lev->height.data();
      all.color = lev->color.data();
      all.stride = lev->w;
    }
    for (int ty = 0; ty < lt.ny; ++ty)
      for (int tx = 0; tx < lt.nx; ++tx) {
        TileBlock& b = lt.tiles[std::size_t(ty) * lt.nx + tx];
        b.x0 = tx * T;
        b.y0 = ty * T;
        b.w = std::min(T, ml.w - b.x0) + 1;
        b.h = std::min(T, ml.h - b.y0) + 1;
        b.bound = ml.bound.data() + std::size_t(b.y0) * ml.w + b.x0;
        b.bound_stride = ml.w;
        if (lev) {
          const std::size_t at = std::size_t(b.y0) * lev->w + b.x0;
          b.height = lev->height.data() + at;
          b.color = lev->color.data() + at;
          b.stride = lev->w;
        }
        b.max_height = -std::numeric_limits<float>::infinity();
        for (int y = 0; y < b.h - 1; ++y)
          for (int x = 0; x < b.w - 1; ++x)
            b.max_height = std::max(b.max_height, b.bound[y * b.bound_stride + x]);
        all.max_height = std::max(all.max_height, b.max_height);
      }
  }
}

// Drape texture box-filtered onto the height samples, row by row.
std::vector<std::uint32_t> colour_map(const Terrain& t) {
  const Heightfield& hf = t.heights;
  std::vector<std::uint32_t> out(static_cast<std::size_t>(hf.width) * hf.height);
  for (int j = 0; j < hf.height; ++j)
    drape_colour_row(t.texture, t.tex_rect, hf.width, hf.height, j,
                     out.data() + static_cast<std::size_t>(j) * hf.width);
  return out;
}

PyramidLevel halve(const PyramidLevel& f, int w, int h) {
  PyramidLevel c;
  c.w = w;
  c.h = h;
  c.height.resize(static_cast<std::size_t>(w) * h);
  c.color.resize(c.height.size());
  for (int j = 0; j < h; ++j) {
    const float* fh[3];
    const std::uint32_t* fc[3];
    for (int b = 0; b < 3; ++b) {
      const std::size_t k = static_cast<std::size_t>(std::clamp(2 * j + b - 1, 0, f.h - 1)) * f.w;
      fh[b] = f.height.data() + k;
      fc[b] = f.color.data() + k;
    }
    const std::size_t k = static_cast<std::size_t>(j) * w;
    halve_row(fh, fc, f.w, 0, w, c.height.data() + k, c.color.data() + k);
  }
  return c;
}

}  // namespace

void drape_colour_row(const Image& tex, const std::array<double, 4>& r, int w, int h, int j,
                      std::uint32_t* out) {
  if (tex.empty()) {
    std::fill(out, out + w, pack_rgba(128, 128, 128));
    return;
  }
  const double fx = w > 1 ? std::abs(r[2]) * tex.width / (w - 1) : 1.0;
  const double fy = h > 1 ? std::abs(r[3]) * tex.height / (h - 1) : 1.0;
  const int nx = std::clamp(int(std::ceil(fx)), 1, 8), ny = std::clamp(int(std::ceil(fy)), 1, 8);
  auto texel = [&](int x, int y, int ch) {
    x = std::clamp(x, 0, tex.width - 1);
    y = std::clamp(y, 0, tex.height - 1);
    return float(tex.px(x, y)[ch]);
  };
  double tv = h > 1 ? double(j) / (h - 1) : 0.5;
  double cy = (r[1] + tv * r[3]) * tex.height - 0.5;
  for (int i = 0; i < w; ++i) {
    double su = w > 1 ? double(i) / (w - 1) : 0.5;
    double cx = (r[0] + su * r[2]) * tex.width - 0.5;
    float acc[3] = {0, 0, 0};
    for (int b = 0; b < ny; ++b) {
      double y = cy + ((b + 0.5) / ny - 0.5) * (ny > 1 ? fy : 0.0);
      int y0 = int(std::floor(y));
      float wy = float(y - y0);
      for (int a = 0; a < nx; ++a) {
        double x = cx + ((a + 0.5) / nx - 0.5) * (nx > 1 ? fx : 0.0);
        int x0 = int(std::floor(x));
        float wx = float(x - x0);
        for (int ch = 0; ch < 3; ++ch) {
          float top = texel(x0, y0, ch) * (1 - wx) + texel(x0 + 1, y0, ch) * wx;
          float bot = texel(x0, y0 + 1, ch) * (1 - wx) + texel(x0 + 1, y0 + 1, ch) * wx;
          acc[ch] += top * (1 - wy) + bot * wy;
        }
      }
    }
    const float n = float(nx * ny);
    out[i] = pack_rgba(acc[0] / n, acc[1] / n, acc[2] / n);
  }
}

void halve_row(const float* const fh[3], const std::uint32_t* const fc[3], int fw, int i0, int i1,
               float* out_h, std::uint32_t* out_c) {
  static constexpr float kTent[3] = {0.25f, 0.5f, 0.25f};
  for (int i = i0; i < i1; ++i) {
    float hs = 0, cs[3] = {0, 0, 0};
    for (int b = 0; b < 3; ++b)
      for (int a = -1; a <= 1; ++a) {
        const int fi = std::clamp(2 * i + a, 0, fw - 1);
        const float wgt = kTent[a + 1] * kTent[b];
        hs += wgt * fh[b][fi];
        for (int ch = 0; ch < 3; ++ch) cs[ch] += wgt * float((fc[b][fi] >> (8 * ch)) & 0xff);
      }
    out_h[i] = hs;
    out_c[i] = pack_rgba(cs[0], cs[1], cs[2]);
  }
}

VoxelTerrain::VoxelTerrain(const Terrain& terrain) : d_(std::make_unique<Data>()) {
  const Heightfield& hf = terrain.heights;
  if (hf.width < 1 || hf.height < 1 ||
      hf.heights.size() != static_cast<std::size_t>(hf.width) * hf.height)
    throw InputError(
        fmt::format("{}: height field {}x{} has no samples", hf.name, hf.width, hf.height));
  Data& d = *d_;
  d.w = hf.width;
  d.h = hf.height;
  d.sx = hf.spacing_x;
  d.sy = hf.spacing_y;
  d.hmin = hf.min_height();
  d.hmax = hf.max_height();

  PyramidLevel base;
  base.w = d.w;
  base.h = d.h;
  base.height = hf.heights;
  base.color = colour_map(terrain);
  d.levels.push_back(std::move(base));
  // Halve while the level still has more than one cell on its longer side.
  for (int L = 1; L < 30; ++L) {
    int w = level_size(d.w, L), h = level_size(d.h, L);
    if (std::max(w, h) <= 2 || (w == d.levels.back().w && h == d.levels.back().h)) break;
    d.levels.push_back(halve(d.levels.back(), w, h));
  }

  // Max over cells, then dilated by one cell.
  const int cw0 = std::max(1, d.w - 1), ch0 = std::max(1, d.h - 1);
  std::vector<float> cells(static_cast<std::size_t>(cw0) * ch0);
  for (int b = 0; b < ch0; ++b)
    for (int a = 0; a < cw0; ++a) {
      float m = -std::numeric_limits<float>::infinity();
      for (int y = b; y <= std::min(b + 1, d.h - 1); ++y)
        for (int x = a; x <= std::min(a + 1, d.w - 1); ++x) m = std::max(m, hf.at(x, y));
      cells[static_cast<std::size_t>(b) * cw0 + a] = m;
    }
  int cw = cw0, ch = ch0;
  for (int k = 0;; ++k) {
    if (k > 0) {
      int nw = (cw + 1) / 2, nh = (ch + 1) / 2;
      std::vector<float> next(static_cast<std::size_t>(nw) * nh);
      for (int b = 0; b < nh; ++b)
        for (int a = 0; a < nw; ++a) {
          float m = -std::numeric_limits<float>::infinity();
          for (int y = 2 * b; y <= std::min(2 * b + 1, ch - 1); ++y)
            for (int x = 2 * a; x <= std::min(2 * a + 1, cw - 1); ++x)
              m = std::max(m, cells[std::size_t(y) * cw + x]);
          next[static_cast<std::size_t>(b) * nw + a] = m;
        }
      cells.swap(next);
      cw = nw;
      ch = nh;
    }
    MaxLevel ml;
    ml.w = cw;
    ml.h = ch;
    ml.bound.resize(cells.size());
    for (int b = 0; b < ch; ++b)
      for (int a = 0; a < cw; ++a) {
        float m = -std::numeric_limits<float>::infinity();
        for (int y = std::max(b - 1, 0); y <= std::min(b + 1, ch - 1); ++y)
          for (int x = std::max(a - 1, 0); x <= std::min(a + 1, cw - 1); ++x)
            m = std::max(m, cells[std::size_t(y) * cw + x]);
        ml.bound[static_cast<std::size_t>(b) * cw + a] = m;
      }
    d.maxes.push_back(std::move(ml));
    if (cw == 1 && ch == 1) break;
  }
  build_tiles(d);
}

VoxelTerrain::~VoxelTerrain() = default;

const TerrainGrid& VoxelTerrain::grid() const {
  return d_->grid;
}

const TileBlock* VoxelTerrain::tile(int level, int tx, int ty) const {
  if (level < 0 || level >= int(d_->tiles.size())) return nullptr;
  const auto& lt = d_->tiles[std::size_t(level)];
  if (tx < 0 || ty < 0 || tx >= lt.nx || ty >= lt.ny) return nullptr;
  return &lt.tiles[std::size_t(ty) * lt.nx + tx];
}

const TileBlock* VoxelTerrain::level_block(int level) const {
  if (level < 0 || level >= int(d_->tiles.size())) return nullptr;
  return &d_->tiles[std::size_t(level)].whole;
}

int VoxelTerrain::levels() const {
  return int(d_->levels.size());
}

VoxelVariant parse_voxel_variant(const std::string& text) {
  if (text == "naive") return VoxelVariant::kNaive;
  if (text == "coherent") return VoxelVariant::kCoherent;
  if (text == "multires") return VoxelVariant::kMultires;
  throw InputError(fmt::format("voxel variant '{}': expected naive, coherent or multires", text));
}

const char* to_string(VoxelVariant v) {
  switch (v) {
    case VoxelVariant::kNaive:
      return "naive";
    case VoxelVariant::kCoherent:
      return "coherent";
    case VoxelVariant::kMultires:
      return "multires";
  }
  return "?";
}

}  // namespace terrasprite
