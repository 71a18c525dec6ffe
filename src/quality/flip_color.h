// SPDX-License-Identifier: MIT
// Internal to quality/: FLIP's per-pixel colour arithmetic (see flip.cpp for
// the paper): colour-space conversions and the per-pixel error formula.
#pragma once
#include <array>
#include <cstdint>

namespace terrasprite::quality::detail {

/// One output row's filtered channels of one image (each `width` floats):
/// CSF-filtered Yy, Cx and the two Cz terms; edge and point responses in x, y.
struct FlipRows {
  const float *a, *rg, *by1, *by2, *edge_x, *edge_y, *point_x, *point_y;
};

class FlipColor {
 public:
  FlipColor();

  /// 8-bit sRGB pixels (1, 3 or 4 channels) to YyCxCz and luminance Y / Yw.
  void to_ycxcz_row(const std::uint8_t* src, int channels, int width, float* yy, float* cx, float* cz,
                    float* lum) const;

  /// Per-pixel FLIP error of `test` against `ref`; Cz = w1 * by1 + w2 * by2.
  void error_row(const FlipRows& ref, const FlipRows& test, float w1, float w2, int width, float* out) const;

  /// HyAB distance ^ 0.7 between Hunt-adjusted green and blue: the remapping's maximum.
  double cmax() const { return cmax_; }

  /// The linear-RGB -> XYZ matrix (sRGB primaries, D65) and its white (RGB = 1).
  static const std::array<double, 9>& rgb_to_xyz();
  static std::array<double, 3> white();

 private:
  std::array<float, 256> linear_;  // sRGB 8-bit -> linear
  std::array<float, 9> to_ycxcz_;  // linear RGB -> XYZ / white
  std::array<float, 9> to_rgb_;    // XYZ / white -> linear RGB
  double cmax_ = 0;
};

/// Built once (thread-safe static).
const FlipColor& flip_color();

}  // namespace terrasprite::quality::detail
