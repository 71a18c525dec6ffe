// SPDX-License-Identifier: MIT
// Synthetic mountains: fractional Brownian motion of gradient noise (Perlin
// 2002, "Improving noise") plus ridged multifractal noise (Musgrave, "Texturing
// and Modeling", ch. 16) and a few thermal-erosion passes (Musgrave, Kolb,
// Mace 1989) to soften slopes steeper than the talus angle.
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/synth.h"

namespace terrasprite {
namespace {

class GradientNoise {
 public:
  explicit GradientNoise(unsigned seed) {
    std::iota(perm_, perm_ + 256, 0);
    std::mt19937 rng(seed);
    std::shuffle(perm_, perm_ + 256, rng);
    for (int i = 0; i < 256; ++i) perm_[256 + i] = perm_[i];
  }
  // Returns roughly [-1, 1].
  double operator()(double x, double y) const {
    int xi = int(std::floor(x)), yi = int(std::floor(y));
    double xf = x - xi, yf = y - yi;
    xi &= 255;
    yi &= 255;
    double u = fade(xf), v = fade(yf);
    int aa = perm_[perm_[xi] + yi], ab = perm_[perm_[xi] + yi + 1];
    int ba = perm_[perm_[xi + 1] + yi], bb = perm_[perm_[xi + 1] + yi + 1];
    double x1 = lerp(grad(aa, xf, yf), grad(ba, xf - 1, yf), u);
    double x2 = lerp(grad(ab, xf, yf - 1), grad(bb, xf - 1, yf - 1), u);
    return lerp(x1, x2, v) * 1.4142;
  }

 private:
  static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
  static double lerp(double a, double b, double t) { return a + (b - a) * t; }
  static double grad(int hash, double x, double y) {
    switch (hash & 7) {
      case 0:
        return x + y;
      case 1:
        return -x + y;
      case 2:
        return x - y;
      case 3:
        return -x - y;
      case 4:
        return x;
      case 5:
        return -x;
      case 6:
        return y;
      default:
        return -y;
    }
  }
  int perm_[512];
};

void thermal_erosion(Heightfield& hf, double talus_m) {
  const int w = hf.width, h = hf.height;
  std::vector<float> delta(hf.heights.size(), 0.f);
  for (int j = 1; j + 1 < h; ++j)
    for (int i = 1; i + 1 < w; ++i) {
      float c = hf.at(i, j);
      // Move a share of the excess over the talus height to the lowest neighbour.
      int bi = i, bj = j;
      float lowest = c;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          if (hf.at(i + di, j + dj) < lowest) {
            lowest = hf.at(i + di, j + dj);
            bi = i + di;
            bj = j + dj;
          }
      float d = c - lowest;
      if (d > talus_m) {
        float move = 0.25f * float(d - talus_m);
        delta[j * w + i] -= move;
        delta[bj * w + bi] += move;
      }
    }
  for (std::size_t p = 0; p < delta.size(); ++p) hf.heights[p] += delta[p];
}

}  // namespace

Heightfield synthesize_terrain(const SynthOptions& o) {
  if (o.size < 2 || o.size > 16385)
    throw InputError(
        fmt::format("synthetic terrain size {}: must be between 2 and 16385 samples", o.size));
  Heightfield hf;
  hf.width = hf.height = o.size;
  hf.spacing_x = hf.spacing_y = o.spacing_m;
  hf.name = "synthetic";
  hf.heights.resize(static_cast<std::size_t>(o.size) * o.size);
  GradientNoise base(o.seed), ridge(o.seed * 7919u + 13u), warp(o.seed * 104729u + 7u);
  // Feature sizes are tied to the terrain extent in metres, so a larger grid
  // at the same spacing shows more mountains, not blurrier ones.
  const double extent = (o.size - 1) * o.spacing_m;
  const double base_wavelength = 6000.0;
  const int octaves = std::clamp(int(std::log2(base_wavelength / o.spacing_m)) + 1, 1, 10);
  tbb::parallel_for(0, o.size, [&](int j) {
    for (int i = 0; i < o.size; ++i) {
      double x = (i * o.spacing_m - extent * 0.5) / base_wavelength + 17.3;
      double y = (j * o.spacing_m - extent * 0.5) / base_wavelength + 5.1;
      // Domain warp breaks the grid-aligned look of plain noise.
      double wx = x + 0.35 * warp(x * 0.5, y * 0.5),
             wy = y + 0.35 * warp(x * 0.5 + 31.7, y * 0.5 + 11.3);
      double fbm = 0, amp = 1, freq = 1;
      for (int k = 0; k < octaves; ++k, amp *= 0.5, freq *= 2)
        fbm += amp * base(wx * freq, wy * freq);
      double rid = 0, weight = 1;
      amp = 1;
      freq = 1;
      for (int k = 0; k < octaves; ++k, amp *= 0.5, freq *= 2.1) {
        double r = 1.0 - std::abs(ridge(wx * freq * 0.8, wy * freq * 0.8));
        r = r * r * weight;
        weight = std::clamp(r * 2.0, 0.0, 1.0);
        rid += amp * r;
      }
      hf.heights[static_cast<std::size_t>(j) * o.size + i] = float(0.55 * fbm + 0.9 * rid);
    }
  });
  auto [lo, hi] = std::minmax_element(hf.heights.begin(), hf.heights.end());
  const float l = *lo, range = std::max(*hi - *lo, 1e-6f);
  for (float& v : hf.heights) v = float((v - l) / range * o.relief_m);
  for (int p = 0; p < o.erosion_passes; ++p) thermal_erosion(hf, o.spacing_m * 0.9);
  return hf;
}

}  // namespace terrasprite
