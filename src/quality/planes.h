// SPDX-License-Identifier: MIT
// Internal to quality/: input checks and conversion of image views to planes.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "terrasprite/common/image.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite::quality::detail {

/// Throws InputError (prefixed with `metric`) for an empty image, a channel
/// count other than 1/3/4, a view too small for its stride, different sizes,
/// or a mask that is neither empty nor width*height bytes.
void check_inputs(const char* metric, const ImageView& reference, const ImageView& test,
                  Mask mask = {});

/// Pixel x of a row as R, G, B (grey replicated, alpha ignored).
inline void rgb_at(const std::uint8_t* row, int channels, int x, int& r, int& g, int& b) {
  const std::uint8_t* p = row + static_cast<std::size_t>(x) * channels;
  if (channels == 1) {
    r = g = b = p[0];
  } else {
    r = p[0], g = p[1], b = p[2];
  }
}

/// Rec. 601 luma, unrounded (the weights Wang's code and ffmpeg use).
inline float luma(int r, int g, int b) {
  return 0.299f * r + 0.587f * g + 0.114f * b;
}

/// A float plane, tightly packed.
struct Plane {
  int width = 0, height = 0;
  std::vector<float> v;
  Plane() = default;
  Plane(int w, int h) : width(w), height(h), v(static_cast<std::size_t>(w) * h) {}
  float* row(int y) { return v.data() + static_cast<std::size_t>(y) * width; }
  const float* row(int y) const { return v.data() + static_cast<std::size_t>(y) * width; }
};

/// Which plane to extract: luma, or one of R, G, B.
enum class Channel { kLuma, kR, kG, kB };
Plane extract(const ImageView& image, Channel channel);
/// Row y of that plane into dst (width floats).
void extract_row(const ImageView& image, Channel channel, int y, float* dst);

/// Number of mask pixels set (the whole image when the mask is empty).
std::size_t mask_count(Mask mask, int width, int height);

}  // namespace terrasprite::quality::detail
