// SPDX-License-Identifier: MIT
// Generated drape textures: elevation ramp x hillshade (the default when no
// texture is given), and the paper's red/green checkerboard (Chen et al. 1999, Fig. 13).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "terrasprite/terrain/texture_gen.h"

namespace terrasprite {
namespace {

struct Stop {
  float t, r, g, b;
};
// Lowland green, dry grass, brown slopes, grey rock, snow.
constexpr Stop kRamp[] = {{0.00f, 62, 110, 52},   {0.25f, 104, 140, 66},  {0.50f, 150, 130, 86},
                          {0.75f, 128, 118, 108}, {0.90f, 200, 196, 192}, {1.00f, 250, 250, 252}};

void ramp(float t, float out[3]) {
  t = std::clamp(t, 0.f, 1.f);
  for (std::size_t k = 1; k < std::size(kRamp); ++k)
    if (t <= kRamp[k].t) {
      const Stop &a = kRamp[k - 1], &b = kRamp[k];
      float s = (t - a.t) / (b.t - a.t);
      out[0] = a.r + (b.r - a.r) * s;
      out[1] = a.g + (b.g - a.g) * s;
      out[2] = a.b + (b.b - a.b) * s;
      return;
    }
  out[0] = out[1] = out[2] = 250;
}

}  // namespace

Image derived_texture(const Heightfield& h, int width, int height) {
  return derived_texture(height_sampler(h), width, height);
}

Image derived_texture(const HeightSampler& h, int width, int height) {
  Image img(width, height);
  const float lo = h.min_height, hi = h.max_height;
  const float range = std::max(hi - lo, 1e-3f);
  // Sun from the north-west, 45 degrees up (the cartographic convention).
  const double az = 315.0 * M_PI / 180.0, alt = 45.0 * M_PI / 180.0;
  const double sun[3] = {std::sin(az) * std::cos(alt), std::cos(az) * std::cos(alt), std::sin(alt)};
  const double ex = h.extent_x(), ey = h.extent_y();
  const double dx = std::max(h.spacing_x, ex / width), dy = std::max(h.spacing_y, ey / height);
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      // Texel centre in world metres (Terrain's mapping: texture spans the sample extent).
      double wx = -ex * 0.5 + (x + 0.5) / width * ex;
      double wy = ey * 0.5 - (y + 0.5) / height * ey;
      double z = h.sample(wx, wy);
      double gx = (h.sample(wx + dx, wy) - h.sample(wx - dx, wy)) / (2 * dx);
      double gy = (h.sample(wx, wy + dy) - h.sample(wx, wy - dy)) / (2 * dy);
      double n[3] = {-gx, -gy, 1.0};
      double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + 1.0);
      double shade = std::max(0.0, (n[0] * sun[0] + n[1] * sun[1] + n[2] * sun[2]) / len);
      double slope = 1.0 - 1.0 / len;  // 0 flat .. 1 vertical
      float c[3];
      ramp(float((z - lo) / range), c);
      // Steep faces show rock whatever their height.
      float rock = float(std::clamp((slope - 0.25) * 3.0, 0.0, 0.7));
      float light = float(0.35 + 0.75 * shade);
      std::uint8_t* p = img.px(x, y);
      for (int k = 0; k < 3; ++k)
        p[k] = std::uint8_t(std::clamp((c[k] * (1 - rock) + 118.f * rock) * light, 0.f, 255.f));
      p[3] = 255;
    }
  });
  return img;
}

Image checker_texture(int squares, int size_px) {
  Image img(size_px, size_px);
  for (int y = 0; y < size_px; ++y)
    for (int x = 0; x < size_px; ++x) {
      bool red = ((x * squares / size_px) + (y * squares / size_px)) % 2 == 0;
      std::uint8_t* p = img.px(x, y);
      p[0] = red ? 220 : 30;
      p[1] = red ? 40 : 180;
      p[2] = 40;
      p[3] = 255;
    }
  return img;
}

}  // namespace terrasprite
