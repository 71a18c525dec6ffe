// SPDX-License-Identifier: MIT
// Layout of VoxelTerrain's pyramids, shared by the ray casters in src/voxel/.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/packed_rgba.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite {

/// One level of the render pyramid. Sample (i, j) of level L sits at level-0
/// grid index (i * 2^L, j * 2^L); samples past the grid's far edge repeat the
/// edge. Row-major, row 0 north. Colour is RGBA8 packed little-endian.
struct PyramidLevel {
  int w = 0, h = 0;
  std::vector<float> height;
  std::vector<std::uint32_t> color;
};

/// One level of the max pyramid over cells: cell (a, b) of level k covers
/// level-0 samples [a*2^k, (a+1)*2^k] x [b*2^k, (b+1)*2^k]; `bound` is the
/// maximum over that cell dilated by one level-k cell on every side, so it
/// bounds every render level L <= k - 2 (whose filters reach < 2^(L+2) samples).
struct MaxLevel {
  int w = 0, h = 0;
  std::vector<float> bound;
  float at(int a, int b) const { return bound[static_cast<std::size_t>(b) * w + a]; }
};

struct VoxelTerrain::Data {
  int w = 0, h = 0;          // level-0 samples
  double sx = 1, sy = 1;     // metres between samples
  float hmin = 0, hmax = 0;  // height range, metres
  std::vector<PyramidLevel> levels;
  std::vector<MaxLevel> maxes;
  // The same pyramids seen as tiles (TerrainTiles): one table per bound level,
  // tiles row-major, viewing `levels` and `maxes` in place.
  TerrainGrid grid;
  struct LevelTiles {
    int nx = 0, ny = 0;
    std::vector<TileBlock> tiles;
    TileBlock whole;  // the level as one block (level_block)
  };
  std::vector<LevelTiles> tiles;

  bool has_area() const { return w >= 2 && h >= 2; }
  // World metres <-> level-0 grid index (fractional).
  double grid_u(double x) const { return x / sx + (w - 1) * 0.5; }
  double grid_v(double y) const { return (h - 1) * 0.5 - y / sy; }
};

/// Row j of the level-0 colour of a w x h sample grid: the drape texture
/// `tex` (Terrain's mapping through `rect`) box-filtered onto the samples;
/// grey without a texture. Writes w packed colours to `out`.
void drape_colour_row(const Image& tex, const std::array<double, 4>& rect, int w, int h, int j,
                      std::uint32_t* out);

/// Samples i0 <= i < i1 of row j of a level halved from its finer level (fw
/// samples a row) with the [1 2 1]/4 tent: fh / fc are the finer rows
/// clamp(2j - 1), clamp(2j), clamp(2j + 1) (clamped to the finer level);
/// out_h[i], out_c[i] are written. The one implementation of a level's
/// samples, in memory and strip-wise alike.
void halve_row(const float* const fh[3], const std::uint32_t* const fc[3], int fw, int i0, int i1,
               float* out_h, std::uint32_t* out_c);

/// floor() as an integer without a libm call (no SSE4.1 in default flags).
/// |x| < 2^62 and not NaN.
inline std::int64_t floor_i64(double x) {
  const std::int64_t i = static_cast<std::int64_t>(x);
  return i - (static_cast<double>(i) > x);
}

inline std::uint32_t pack_rgba(float r, float g, float b) {
  auto c = [](float v) { return std::uint32_t(std::clamp(v + 0.5f, 0.f, 255.f)); };
  return c(r) | (c(g) << 8) | (c(b) << 16) | 0xff000000u;
}

/// Bilinear height of `lev` at fractional level coordinates (i, j), clamped.
inline float bilinear_height(const PyramidLevel& lev, double i, double j) {
  i = std::clamp(i, 0.0, double(lev.w - 1));
  j = std::clamp(j, 0.0, double(lev.h - 1));
  int i0 = std::min(int(i), std::max(lev.w - 2, 0)), j0 = std::min(int(j), std::max(lev.h - 2, 0));
  int i1 = std::min(i0 + 1, lev.w - 1), j1 = std::min(j0 + 1, lev.h - 1);
  float fi = float(i - i0), fj = float(j - j0);
  const float* r0 = lev.height.data() + std::size_t(j0) * lev.w;
  const float* r1 = lev.height.data() + std::size_t(j1) * lev.w;
  float a = r0[i0] + (r0[i1] - r0[i0]) * fi;
  float b = r1[i0] + (r1[i1] - r1[i0]) * fi;
  return a + (b - a) * fj;
}

/// Bilinear colour of `lev` at (i, j), clamped; channels as floats 0..255.
inline void bilinear_color(const PyramidLevel& lev, double i, double j, float out[3]) {
  i = std::clamp(i, 0.0, double(lev.w - 1));
  j = std::clamp(j, 0.0, double(lev.h - 1));
  int i0 = std::min(int(i), std::max(lev.w - 2, 0)), j0 = std::min(int(j), std::max(lev.h - 2, 0));
  int i1 = std::min(i0 + 1, lev.w - 1), j1 = std::min(j0 + 1, lev.h - 1);
  float fi = float(i - i0), fj = float(j - j0);
  const std::uint32_t* c = lev.color.data();
  std::uint32_t p[4] = {c[std::size_t(j0) * lev.w + i0], c[std::size_t(j0) * lev.w + i1],
                        c[std::size_t(j1) * lev.w + i0], c[std::size_t(j1) * lev.w + i1]};
  float wgt[4] = {(1 - fi) * (1 - fj), fi * (1 - fj), (1 - fi) * fj, fi * fj};
  for (int ch = 0; ch < 3; ++ch) {
    float s = 0;
    for (int k = 0; k < 4; ++k) s += wgt[k] * float((p[k] >> (8 * ch)) & 0xff);
    out[ch] = s;
  }
}

/// Bilinear packed colour of `lev` at (i, j), clamped; 8-bit weights.
inline std::uint32_t bilinear_color_packed(const PyramidLevel& lev, double i, double j) {
  i = std::clamp(i, 0.0, double(lev.w - 1));
  j = std::clamp(j, 0.0, double(lev.h - 1));
  int i0 = std::min(int(i), std::max(lev.w - 2, 0)), j0 = std::min(int(j), std::max(lev.h - 2, 0));
  int i1 = std::min(i0 + 1, lev.w - 1), j1 = std::min(j0 + 1, lev.h - 1);
  const std::uint32_t fi = std::uint32_t((i - i0) * 256.0 + 0.5),
                      fj = std::uint32_t((j - j0) * 256.0 + 0.5);
  const std::uint32_t* r0 = lev.color.data() + std::size_t(j0) * lev.w;
  const std::uint32_t* r1 = lev.color.data() + std::size_t(j1) * lev.w;
  return lerp_packed(lerp_packed(r0[i0], r0[i1], fi), lerp_packed(r1[i0], r1[i1], fi), fj);
}

}  // namespace terrasprite
