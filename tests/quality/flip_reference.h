// SPDX-License-Identifier: MIT
// A slow, straightforward LDR-FLIP written again from the paper's formulas
// (Andersson et al. 2020): float64 throughout, full 2D kernels normalised in
// 2D, direct 2D convolution with edge-replicating borders, libm pow/cbrt. It
// shares no code with src/quality/, so it checks the separable, streamed,
// float, fast-math implementation.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "terrasprite/common/image.h"

namespace terrasprite::quality::testing {

struct FlipReference {
  std::vector<double> map, color, feature;  // final error, Ec and Ef per pixel
  double mean = 0;
};

namespace ref {

using Plane = std::vector<double>;
constexpr double kPi = std::numbers::pi;

inline std::array<double, 9> rgb2xyz() {
  return {10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794,
          2613072.0 / 12288897,  8788810.0 / 12288897, 887015.0 / 12288897,
          1425312.0 / 73733382,  8788810.0 / 73733382, 70074185.0 / 73733382};
}
inline std::array<double, 3> mul(const std::array<double, 9>& m, double a, double b, double c) {
  return {m[0] * a + m[1] * b + m[2] * c, m[3] * a + m[4] * b + m[5] * c,
          m[6] * a + m[7] * b + m[8] * c};
}
inline std::array<double, 9> inverse(const std::array<double, 9>& m) {
  const double d = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                   m[2] * (m[3] * m[7] - m[4] * m[6]);
  return {(m[4] * m[8] - m[5] * m[7]) / d, (m[2] * m[7] - m[1] * m[8]) / d,
          (m[1] * m[5] - m[2] * m[4]) / d, (m[5] * m[6] - m[3] * m[8]) / d,
          (m[0] * m[8] - m[2] * m[6]) / d, (m[2] * m[3] - m[0] * m[5]) / d,
          (m[3] * m[7] - m[4] * m[6]) / d, (m[1] * m[6] - m[0] * m[7]) / d,
          (m[0] * m[4] - m[1] * m[3]) / d};
}
inline std::array<double, 3> white() {
  return mul(rgb2xyz(), 1, 1, 1);
}

inline std::array<double, 3> hunt_lab(double r, double g, double b) {
  const auto xyz = mul(rgb2xyz(), r, g, b);
  const auto w = white();
  const double d = 6.0 / 29;
  double f[3];
  for (int i = 0; i < 3; ++i) {
    const double t = xyz[i] / w[i];
    f[i] = t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29;
  }
  const double L = 116 * f[1] - 16;
  return {L, 0.01 * L * 500 * (f[0] - f[1]), 0.01 * L * 200 * (f[1] - f[2])};
}

inline double hyab(const std::array<double, 3>& p, const std::array<double, 3>& q) {
  return std::abs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

// Direct 2D convolution (kernel symmetric or antisymmetric: the feature
// magnitudes do not care about the flip), borders replicate the edge.
inline Plane convolve(const Plane& in, int w, int h, const std::vector<double>& k, int r) {
  Plane out(in.size(), 0.0);
  const int n = 2 * r + 1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int j = -r; j <= r; ++j)
        for (int i = -r; i <= r; ++i)
          s += k[(j + r) * n + (i + r)] *
               in[std::clamp(y + j, 0, h - 1) * w + std::clamp(x + i, 0, w - 1)];
      out[y * w + x] = s;
    }
  return out;
}

}  // namespace ref

inline FlipReference flip_reference(const Image& reference, const Image& test, double ppd = 67.02) {
  using namespace ref;
  const int w = reference.width, h = reference.height, n = w * h;
  const auto m = rgb2xyz(), minv = inverse(m);
  const auto wt = white();
  // sRGB -> linear -> XYZ -> YyCxCz, per image.
  auto opponent = [&](const Image& im, Plane& yy, Plane& cx, Plane& cz) {
    yy.resize(n), cx.resize(n), cz.resize(n);
    for (int i = 0; i < n; ++i) {
      double lin[3];
      for (int c = 0; c < 3; ++c) {
        const double v = im.rgba[4 * i + c] / 255.0;
        lin[c] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
      }
      const auto xyz = mul(m, lin[0], lin[1], lin[2]);
      const double x = xyz[0] / wt[0], y = xyz[1] / wt[1], z = xyz[2] / wt[2];
      yy[i] = 116 * y - 16, cx[i] = 500 * (x - y), cz[i] = 200 * (y - z);
    }
  };
  // CSF kernels: a1 sqrt(pi/b1) exp(-pi^2 d^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 d^2/b2), d in degrees,
  // 2D-normalised.
  const int r = static_cast<int>(std::ceil(3 * std::sqrt(0.04 / (2 * kPi * kPi)) * ppd));
  auto csf = [&](double a1, double b1, double a2, double b2) {
    std::vector<double> k((2 * r + 1) * (2 * r + 1));
    double s = 0;
    for (int j = -r; j <= r; ++j)
      for (int i = -r; i <= r; ++i) {
        const double d2 = (i * i + j * j) / (ppd * ppd);
        s += k[(j + r) * (2 * r + 1) + i + r] =
            a1 * std::sqrt(kPi / b1) * std::exp(-kPi * kPi * d2 / b1) +
            a2 * std::sqrt(kPi / b2) * std::exp(-kPi * kPi * d2 / b2);
      }
    for (double& v : k) v /= s;
    return k;
  };
  const auto k_a = csf(1, 0.0047, 0, 1e-5), k_rg = csf(1, 0.0053, 0, 1e-5),
             k_by = csf(34.1, 0.04, 13.5, 0.025);
  // Feature kernels: x-derivatives of a Gaussian, sd = 0.5 * 0.082 * ppd, signed parts normalised
  // to +-1.
  const double sd = 0.5 * 0.082 * ppd;
  const int fr = static_cast<int>(std::ceil(3 * sd));
  const int fn = 2 * fr + 1;
  auto feature_kernel = [&](bool point, bool transpose) {
    std::vector<double> k(fn * fn);
    double pos = 0, neg = 0;
    for (int j = -fr; j <= fr; ++j)
      for (int i = -fr; i <= fr; ++i) {
        const double g = std::exp(-(i * i + j * j) / (2 * sd * sd));
        const double v = point ? (i * i / (sd * sd) - 1) * g : -i * g;
        (v > 0 ? pos : neg) += v;
        k[transpose ? (i + fr) * fn + (j + fr) : (j + fr) * fn + (i + fr)] = v;
      }
    for (double& v : k) v = v > 0 ? v / pos : (v < 0 ? -v / neg : 0);
    return k;
  };
  const auto ex = feature_kernel(false, false), ey = feature_kernel(false, true);
  const auto px = feature_kernel(true, false), py = feature_kernel(true, true);

  Plane yy[2], cx[2], cz[2];
  opponent(reference, yy[0], cx[0], cz[0]);
  opponent(test, yy[1], cx[1], cz[1]);
  std::vector<std::array<double, 3>> lab[2];
  Plane edge[2], point[2];
  for (int k = 0; k < 2; ++k) {
    const Plane fy = convolve(yy[k], w, h, k_a, r), fx = convolve(cx[k], w, h, k_rg, r),
                fz = convolve(cz[k], w, h, k_by, r);
    lab[k].resize(n);
    Plane lum(n);
    for (int i = 0; i < n; ++i) {
      const double y = (fy[i] + 16) / 116, x = fx[i] / 500 + y, z = y - fz[i] / 200;
      auto rgb = mul(minv, x * wt[0], y * wt[1], z * wt[2]);
      for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
      lab[k][i] = hunt_lab(rgb[0], rgb[1], rgb[2]);
      lum[i] = (yy[k][i] + 16) / 116;
    }
    const Plane a = convolve(lum, w, h, ex, fr), b = convolve(lum, w, h, ey, fr);
    const Plane c = convolve(lum, w, h, px, fr), d = convolve(lum, w, h, py, fr);
    edge[k].resize(n), point[k].resize(n);
    for (int i = 0; i < n; ++i)
      edge[k][i] = std::hypot(a[i], b[i]), point[k][i] = std::hypot(c[i], d[i]);
  }
  const double cmax = std::pow(hyab(hunt_lab(0, 1, 0), hunt_lab(0, 0, 1)), 0.7);
  const double pc = 0.4, pt = 0.95;
  FlipReference out;
  out.map.resize(n), out.color.resize(n), out.feature.resize(n);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double dc = std::pow(hyab(lab[0][i], lab[1][i]), 0.7);
    const double ec = dc < pc * cmax ? pt / (pc * cmax) * dc
                                     : pt + (dc - pc * cmax) / (cmax - pc * cmax) * (1 - pt);
    const double df =
        std::max(std::abs(edge[0][i] - edge[1][i]), std::abs(point[0][i] - point[1][i]));
    const double ef = std::pow(df / std::sqrt(2.0), 0.5);
    out.color[i] = ec, out.feature[i] = ef;
    sum += out.map[i] = std::pow(ec, 1 - ef);
  }
  out.mean = sum / n;
  return out;
}

}  // namespace terrasprite::quality::testing
