// SPDX-License-Identifier: MIT
// Test images generated in code, degradations, and finding external tools.
#pragma once
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "terrasprite/common/image.h"

namespace terrasprite::quality::testing {

/// A deterministic "scene": smooth colour gradients, a few sharp-edged shapes
/// and fine texture, so every metric has structure to react to.
inline Image scene(int w, int h, unsigned seed = 1) {
  Image im(w, h);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double fx = 0.05 + 0.1 * u(rng), fy = 0.04 + 0.1 * u(rng), ph = 6.28 * u(rng);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double s = std::sin(fx * x + ph) * std::cos(fy * y);
      double r = 40 + 150.0 * x / w + 30 * s, g = 60 + 120.0 * y / h + 40 * s,
             b = 120 + 60 * std::sin(0.3 * x + 0.2 * y);
      if ((x / 16 + y / 16) % 5 == 0) r = 230, g = 200, b = 40;  // sharp-edged blocks
      if ((x - w / 2) * (x - w / 2) + (y - h / 3) * (y - h / 3) < w * h / 40) b = 250;  // a disc
      std::uint8_t* p = im.px(x, y);
      p[0] = static_cast<std::uint8_t>(std::clamp(r, 0.0, 255.0));
      p[1] = static_cast<std::uint8_t>(std::clamp(g, 0.0, 255.0));
      p[2] = static_cast<std::uint8_t>(std::clamp(b, 0.0, 255.0));
      p[3] = 255;
    }
  return im;
}

/// A uniform image.
inline Image flat(int w, int h, std::array<std::uint8_t, 3> c) {
  Image im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = im.px(x, y);
      p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
    }
  return im;
}

/// Adds Gaussian noise of standard deviation `sigma` (8-bit units), clamped.
inline Image noisy(const Image& in, double sigma, unsigned seed = 7) {
  Image out = in;
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, sigma);
  for (std::size_t i = 0; i < out.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    out.rgba[i] = static_cast<std::uint8_t>(std::clamp(std::lround(in.rgba[i] + n(rng)), 0L, 255L));
  }
  return out;
}

/// `passes` rounds of a 3x3 box blur (edges clamped).
inline Image blurred(const Image& in, int passes) {
  Image cur = in;
  for (int p = 0; p < passes; ++p) {
    Image next = cur;
    for (int y = 0; y < cur.height; ++y)
      for (int x = 0; x < cur.width; ++x)
        for (int c = 0; c < 3; ++c) {
          int s = 0;
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              s += cur.px(std::clamp(x + dx, 0, cur.width - 1),
                          std::clamp(y + dy, 0, cur.height - 1))[c];
          next.px(x, y)[c] = static_cast<std::uint8_t>((s + 4) / 9);
        }
    cur = std::move(next);
  }
  return cur;
}

/// Whether `path` (absolute) is an executable file.
inline bool executable(const char* path) {
  return ::access(path, X_OK) == 0;
}

}  // namespace terrasprite::quality::testing
