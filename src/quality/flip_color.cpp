// SPDX-License-Identifier: MIT
// FLIP's colour arithmetic (Andersson et al. 2020, see flip.cpp). The
// linear-RGB/XYZ matrix is the rational one of NVIDIA's reference code; the
// white point is that matrix applied to RGB = (1, 1, 1).
// The per-pixel loop vectorises only if sqrt need not set errno (we never
// read it; CMakeLists.txt adds -fno-math-errno for this file, and std::sqrt
// is then the exact vector instruction rather than fast_sqrt's three Newton
// steps) and selects between floats may evaluate both sides (FP traps are
// masked anyway). Neither changes a result: this is not -ffast-math, no
// reassociation, no reciprocal approximations; values stay IEEE.
// The fast clone is x86-64-v3 (AVX2 + FMA) with a * b + c contracted to fused
// multiply-adds (fp-contract=fast, off by default under -std=c++20): the
// colour matrices and the exp/log polynomials are chains of them. That changes
// results against the baseline clone by float rounding only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("no-math-errno", "no-trapping-math", "fp-contract=fast")
#endif
#include "quality/flip_color.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/simd.h"
#include "quality/fast_math.h"

namespace terrasprite::quality::detail {

namespace {

constexpr double kDelta = 6.0 / 29.0;  // CIELAB's linear/cube-root switch
constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f;

std::array<double, 9> invert(const std::array<double, 9>& m) {
  const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                     m[2] * (m[3] * m[7] - m[4] * m[6]);
  return {(m[4] * m[8] - m[5] * m[7]) / det, (m[2] * m[7] - m[1] * m[8]) / det,
          (m[1] * m[5] - m[2] * m[4]) / det, (m[5] * m[6] - m[3] * m[8]) / det,
          (m[0] * m[8] - m[2] * m[6]) / det, (m[2] * m[3] - m[0] * m[5]) / det,
          (m[3] * m[7] - m[4] * m[6]) / det, (m[1] * m[6] - m[0] * m[7]) / det,
          (m[0] * m[4] - m[1] * m[3]) / det};
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

inline float clamp01(float v) {
  return v < 0 ? 0 : (v > 1 ? 1 : v);
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
  for (int i = 0; i < 9; ++i)
    to_ycxcz_[i] = static_cast<float>(scaled[i]), to_rgb_[i] = static_cast<float>(inv[i]);
  const auto green = hunt_lab(0, 1, 0), blue = hunt_lab(0, 0, 1);
  const double hyab =
      std::abs(green[0] - blue[0]) + std::hypot(green[1] - blue[1], green[2] - blue[2]);
  cmax_ = std::pow(hyab, kQc);
}

// Two passes: the 8-bit -> linear lookups (scalar: a gather from a 256-entry
// table, any channel layout) into a small SoA buffer, then the matrix in a
// plain loop that GCC vectorises (one interleaved scalar loop did neither and
// cost a fifth of FLIP's instructions).
TS_CLONES_V3 void FlipColor::to_ycxcz_row(const std::uint8_t* src, int channels, int width,
                                          float* yy, float* cx, float* cz, float* lum) const {
  const float m0 = to_ycxcz_[0], m1 = to_ycxcz_[1], m2 = to_ycxcz_[2], m3 = to_ycxcz_[3],
              m4 = to_ycxcz_[4], m5 = to_ycxcz_[5], m6 = to_ycxcz_[6], m7 = to_ycxcz_[7],
              m8 = to_ycxcz_[8];
  const int step = channels, g_off = channels == 1 ? 0 : 1, b_off = channels == 1 ? 0 : 2;
  float* __restrict oy = yy, * __restrict ox = cx, * __restrict oz = cz, * __restrict ol = lum;
  constexpr int kChunk = 256;
  float R[kChunk], G[kChunk], B[kChunk];
  for (int x0 = 0; x0 < width; x0 += kChunk) {
    const int n = std::min(kChunk, width - x0);
    const std::uint8_t* p = src + static_cast<std::size_t>(x0) * step;
    for (int j = 0; j < n; ++j, p += step)
      R[j] = linear_[p[0]], G[j] = linear_[p[g_off]], B[j] = linear_[p[b_off]];
    for (int j = 0; j < n; ++j) {
      const float r = R[j], g = G[j], b = B[j];
      const float x = m0 * r + m1 * g + m2 * b;
      const float y = m3 * r + m4 * g + m5 * b;
      const float z = m6 * r + m7 * g + m8 * b;
      oy[x0 + j] = 116 * y - 16;
      ox[x0 + j] = 500 * (x - y);
      oz[x0 + j] = 200 * (y - z);
      ol[x0 + j] = y;  // (Yy + 16) / 116: the feature pipeline's achromatic input
    }
  }
}

TS_CLONES_V3 void FlipColor::error_row(const FlipRows& ref, const FlipRows& test, float w1,
                                       float w2, int width, float* out) const {
  const float cmax = static_cast<float>(cmax_);
  const float pccmax = kPc * cmax;
  const float inv_sqrt2 = static_cast<float>(1 / std::numbers::sqrt2);
  // Matrices as scalar locals (a local array read through a reference keeps
  // loads in the loop that GCC will not vectorise).
  const float r0 = to_rgb_[0], r1 = to_rgb_[1], r2 = to_rgb_[2], r3 = to_rgb_[3], r4 = to_rgb_[4],
              r5 = to_rgb_[5], r6 = to_rgb_[6], r7 = to_rgb_[7], r8 = to_rgb_[8];
  const float x0 = to_ycxcz_[0], x1 = to_ycxcz_[1], x2 = to_ycxcz_[2], x3 = to_ycxcz_[3],
              x4 = to_ycxcz_[4], x5 = to_ycxcz_[5], x6 = to_ycxcz_[6], x7 = to_ycxcz_[7],
              x8 = to_ycxcz_[8];
  // Filtered YyCxCz -> linear RGB, clamped to the RGB box -> Hunt-adjusted CIELAB.
  auto to_lab = [=](float yy, float cx, float cz, float& L, float& A, float& B) {
    const float y = (yy + 16) * (1.0f / 116), x = cx * (1.0f / 500) + y, z = y - cz * (1.0f / 200);
    const float r = clamp01(r0 * x + r1 * y + r2 * z);
    const float g = clamp01(r3 * x + r4 * y + r5 * z);
    const float b = clamp01(r6 * x + r7 * y + r8 * z);
    const float fx = lab_f(x0 * r + x1 * g + x2 * b);
    const float fy = lab_f(x3 * r + x4 * g + x5 * b);
    const float fz = lab_f(x6 * r + x7 * g + x8 * b);
    L = 116 * fy - 16;
    A = 0.01f * L * 500 * (fx - fy);  // Hunt: chroma scales with lightness
    B = 0.01f * L * 200 * (fy - fz);
  };
  // Row pointers in restrict locals: otherwise every store to `out` could
  // change them, they are reloaded per pixel and the loop does not vectorise.
  const float* __restrict ya = ref.a, * __restrict yrg = ref.rg, * __restrict yb1 = ref.by1, * __restrict yb2 = ref.by2;
  const float* __restrict ta = test.a, * __restrict trg = test.rg, * __restrict tb1 = test.by1, * __restrict tb2 = test.by2;
  const float* __restrict rex = ref.edge_x, * __restrict rey = ref.edge_y, * __restrict rpx = ref.point_x, * __restrict rpy = ref.point_y;
  const float* __restrict tex = test.edge_x, * __restrict tey = test.edge_y, * __restrict tpx = test.point_x, * __restrict tpy = test.point_y;
  // Chunks of simple loops, each of which GCC vectorises on its own.
  constexpr int kChunk = 64;
  float L1[kChunk], A1[kChunk], B1[kChunk], L2[kChunk], A2[kChunk], B2[kChunk];
  for (int x0 = 0; x0 < width; x0 += kChunk) {
    const int n = std::min(kChunk, width - x0);
    for (int j = 0; j < n; ++j) {
      const int i = x0 + j;
      to_lab(ya[i], yrg[i], w1 * yb1[i] + w2 * yb2[i], L1[j], A1[j], B1[j]);
    }
    for (int j = 0; j < n; ++j) {
      const int i = x0 + j;
      to_lab(ta[i], trg[i], w1 * tb1[i] + w2 * tb2[i], L2[j], A2[j], B2[j]);
    }
    for (int j = 0; j < n; ++j) {
      const int i = x0 + j;
      const float da = A1[j] - A2[j], db = B1[j] - B2[j];
      const float hyab = std::fabs(L1[j] - L2[j]) + std::sqrt(da * da + db * db);
      const float dc = fast_pow(hyab, kQc);
      const float ec =
          dc < pccmax ? (kPt / pccmax) * dc : kPt + (dc - pccmax) / (cmax - pccmax) * (1 - kPt);
      const float e1 = std::sqrt(rex[i] * rex[i] + rey[i] * rey[i]);
      const float e2 = std::sqrt(tex[i] * tex[i] + tey[i] * tey[i]);
      const float p1 = std::sqrt(rpx[i] * rpx[i] + rpy[i] * rpy[i]);
      const float p2 = std::sqrt(tpx[i] * tpx[i] + tpy[i] * tpy[i]);
      const float df = std::max(std::fabs(e1 - e2), std::fabs(p1 - p2));
      const float ef = std::sqrt(df * inv_sqrt2);  // ^ qf, qf = 0.5
      out[i] = fast_pow(ec, 1 - ef);
    }
  }
}

const FlipColor& flip_color() {
  static const FlipColor c;
  return c;
}

}  // namespace terrasprite::quality::detail
