// SPDX-License-Identifier: MIT
// FLIP's colour arithmetic (Andersson et al. 2020, see flip.cpp). The
// linear-RGB/XYZ matrix is the rational one of NVIDIA's reference code; the
// white point is that matrix applied to RGB = (1, 1, 1).
#include "quality/flip_color.h"

#include <cmath>
#include <numbers>

#include "quality/fast_math.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TS_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TS_CLONES
#endif

namespace terrasprite::quality::detail {

namespace {

constexpr double kDelta = 6.0 / 29.0;  // CIELAB's linear/cube-root switch
constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f;

std::array<double, 9> invert(const std::array<double, 9>& m) {
  const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                     m[2] * (m[3] * m[7] - m[4] * m[6]);
  return {(m[4] * m[8] - m[5] * m[7]) / det, (m[2] * m[7] - m[1] * m[8]) / det, (m[1] * m[5] - m[2] * m[4]) / det,
          (m[5] * m[6] - m[3] * m[8]) / det, (m[0] * m[8] - m[2] * m[6]) / det, (m[2] * m[3] - m[0] * m[5]) / det,
          (m[3] * m[7] - m[4] * m[6]) / det, (m[1] * m[6] - m[0] * m[7]) / det, (m[0] * m[4] - m[1] * m[3]) / det};
}

// Hunt-adjusted CIELAB of a linear RGB colour, in double (for cmax).
std::array<double, 3> hunt_lab(double r, double g, double b) {
  const auto& m = FlipColor::rgb_to_xyz();
  const auto wt = FlipColor::white();
  double t[3];
  for (int i = 0; i < 3; ++i) {
    const double v = (m[3 * i] * r + m[3 * i + 1] * g + m[3 * i + 2] * b) / wt[i];
    t[i] = v > kDelta * kDelta * kDelta ? std::cbrt(v) : v / (3 * kDelta * kDelta) + 4.0 / 29.0;
  }
  const double L = 116 * t[1] - 16;
  return {L, 0.01 * L * 500 * (t[0] - t[1]), 0.01 * L * 200 * (t[1] - t[2])};
}

// CIELAB's f(t) in float: cube root above delta^3, linear below.
inline float lab_f(float t) {
  constexpr float d3 = static_cast<float>(kDelta * kDelta * kDelta);
  const float c = fast_cbrt(t > d3 ? t : d3);
  return t > d3 ? c : t * static_cast<float>(1 / (3 * kDelta * kDelta)) + 4.0f / 29.0f;
}

inline float clamp01(float v) { return v < 0 ? 0 : (v > 1 ? 1 : v); }

// Filtered YyCxCz -> linear RGB, clamped to the RGB box -> Hunt-adjusted CIELAB.
inline void filtered_to_lab(const std::array<float, 9>& to_rgb, const std::array<float, 9>& to_xyz, float yy,
                            float cx, float cz, float& L, float& A, float& B) {
  const float y = (yy + 16) * (1.0f / 116), x = cx * (1.0f / 500) + y, z = y - cz * (1.0f / 200);
  const float r = clamp01(to_rgb[0] * x + to_rgb[1] * y + to_rgb[2] * z);
  const float g = clamp01(to_rgb[3] * x + to_rgb[4] * y + to_rgb[5] * z);
  const float b = clamp01(to_rgb[6] * x + to_rgb[7] * y + to_rgb[8] * z);
  const float fx = lab_f(to_xyz[0] * r + to_xyz[1] * g + to_xyz[2] * b);
  const float fy = lab_f(to_xyz[3] * r + to_xyz[4] * g + to_xyz[5] * b);
  const float fz = lab_f(to_xyz[6] * r + to_xyz[7] * g + to_xyz[8] * b);
  L = 116 * fy - 16;
  A = 0.01f * L * 500 * (fx - fy);  // Hunt: chroma scales with lightness
  B = 0.01f * L * 200 * (fy - fz);
}

}  // namespace

const std::array<double, 9>& FlipColor::rgb_to_xyz() {
  static const std::array<double, 9> m = {
      10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794,
      2613072.0 / 12288897,  8788810.0 / 12288897, 887015.0 / 12288897,
      1425312.0 / 73733382,  8788810.0 / 73733382, 70074185.0 / 73733382};
  return m;
}

std::array<double, 3> FlipColor::white() {
  const auto& m = rgb_to_xyz();
  return {m[0] + m[1] + m[2], m[3] + m[4] + m[5], m[6] + m[7] + m[8]};
}

FlipColor::FlipColor() {
  for (int i = 0; i < 256; ++i) {
    const double c = i / 255.0;
    linear_[i] = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
  }
  const auto& m = rgb_to_xyz();
  const auto wt = white();
  std::array<double, 9> scaled;  // rows divided by the white: XYZ / white
  for (int i = 0; i < 9; ++i) scaled[i] = m[i] / wt[i / 3];
  const auto inv = invert(scaled);
  for (int i = 0; i < 9; ++i) to_ycxcz_[i] = static_cast<float>(scaled[i]), to_rgb_[i] = static_cast<float>(inv[i]);
  const auto green = hunt_lab(0, 1, 0), blue = hunt_lab(0, 0, 1);
  const double hyab = std::abs(green[0] - blue[0]) + std::hypot(green[1] - blue[1], green[2] - blue[2]);
  cmax_ = std::pow(hyab, kQc);
}

void FlipColor::to_ycxcz_row(const std::uint8_t* src, int channels, int width, float* yy, float* cx, float* cz,
                             float* lum) const {
  const auto& m = to_ycxcz_;
  for (int i = 0; i < width; ++i) {
    const std::uint8_t* p = src + static_cast<std::size_t>(i) * channels;
    const float r = linear_[p[0]], g = linear_[channels == 1 ? p[0] : p[1]], b = linear_[channels == 1 ? p[0] : p[2]];
    const float x = m[0] * r + m[1] * g + m[2] * b;
    const float y = m[3] * r + m[4] * g + m[5] * b;
    const float z = m[6] * r + m[7] * g + m[8] * b;
    yy[i] = 116 * y - 16;
    cx[i] = 500 * (x - y);
    cz[i] = 200 * (y - z);
    lum[i] = y;  // (Yy + 16) / 116: the feature pipeline's achromatic input
  }
}

TS_CLONES void FlipColor::error_row(const FlipRows& ref, const FlipRows& test, float w1, float w2, int width,
                                    float* out) const {
  const float cmax = static_cast<float>(cmax_);
  const float pccmax = kPc * cmax;
  const float inv_sqrt2 = static_cast<float>(1 / std::numbers::sqrt2);
  const std::array<float, 9> to_rgb = to_rgb_, to_xyz = to_ycxcz_;  // locals: no aliasing with `out`
  for (int i = 0; i < width; ++i) {
    float L1, A1, B1, L2, A2, B2;
    filtered_to_lab(to_rgb, to_xyz, ref.a[i], ref.rg[i], w1 * ref.by1[i] + w2 * ref.by2[i], L1, A1, B1);
    filtered_to_lab(to_rgb, to_xyz, test.a[i], test.rg[i], w1 * test.by1[i] + w2 * test.by2[i], L2, A2, B2);
    const float da = A1 - A2, db = B1 - B2;
    const float hyab = std::fabs(L1 - L2) + std::sqrt(da * da + db * db);
    const float dc = fast_pow(hyab, kQc);
    const float ec = dc < pccmax ? (kPt / pccmax) * dc : kPt + (dc - pccmax) / (cmax - pccmax) * (1 - kPt);

    const float e1 = std::sqrt(ref.edge_x[i] * ref.edge_x[i] + ref.edge_y[i] * ref.edge_y[i]);
    const float e2 = std::sqrt(test.edge_x[i] * test.edge_x[i] + test.edge_y[i] * test.edge_y[i]);
    const float p1 = std::sqrt(ref.point_x[i] * ref.point_x[i] + ref.point_y[i] * ref.point_y[i]);
    const float p2 = std::sqrt(test.point_x[i] * test.point_x[i] + test.point_y[i] * test.point_y[i]);
    const float df = std::max(std::fabs(e1 - e2), std::fabs(p1 - p2));
    const float ef = std::sqrt(df * inv_sqrt2);  // ^ qf, qf = 0.5
    out[i] = fast_pow(ec, 1 - ef);
  }
}

const FlipColor& flip_color() {
  static const FlipColor c;
  return c;
}

}  // namespace terrasprite::quality::detail
