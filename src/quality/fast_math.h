// SPDX-License-Identifier: MIT
// Internal to quality/: branch-free float cbrt, exp, log and pow that GCC can
// vectorise (the libm calls cannot be without -ffast-math, which we do not
// use). Accurate to a few float ulps over the ranges FLIP feeds them:
// exp/log are the Cephes single-precision polynomials (S. L. Moshier), cbrt
// is a bit-level guess refined by three Newton steps.
#pragma once
#include <bit>
#include <cstdint>

namespace terrasprite::quality::detail {

/// Natural log for x > 0 (finite, normal).
inline float fast_log(float x) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
  int e = static_cast<int>((bits >> 23) & 0xff) - 126;
  float m = std::bit_cast<float>((bits & 0x807fffffu) | 0x3f000000u);  // m in [0.5, 1)
  // Keep m in [sqrt(1/2), sqrt(2)) so the polynomial's argument stays small.
  const bool low = m < 0.707106781186547524f;
  e -= low ? 1 : 0;
  m = low ? m + m - 1.0f : m - 1.0f;
  const float z = m * m;
  float y = 7.0376836292E-2f;
  y = y * m - 1.1514610310E-1f;
  y = y * m + 1.1676998740E-1f;
  y = y * m - 1.2420140846E-1f;
  y = y * m + 1.4249322787E-1f;
  y = y * m - 1.6668057665E-1f;
  y = y * m + 2.0000714765E-1f;
  y = y * m - 2.4999993993E-1f;
  y = y * m + 3.3333331174E-1f;
  y = y * m * z;
  const float fe = static_cast<float>(e);
  y += fe * -2.12194440e-4f;
  y += -0.5f * z;
  return m + y + fe * 0.693359375f;
}

/// e^x, x clamped to [-87, 88] (results stay normal floats).
inline float fast_exp(float x) {
  x = x < -87.0f ? -87.0f : (x > 88.0f ? 88.0f : x);
  float fx = x * 1.44269504088896341f + 0.5f;
  int n = static_cast<int>(fx);  // truncates: step down for negatives to floor
  n -= static_cast<float>(n) > fx ? 1 : 0;
  fx = static_cast<float>(n);
  x -= fx * 0.693359375f;
  x -= fx * -2.12194440e-4f;
  const float z = x * x;
  float y = 1.9875691500E-4f;
  y = y * x + 1.3981999507E-3f;
  y = y * x + 8.3334519073E-3f;
  y = y * x + 4.1665795894E-2f;
  y = y * x + 1.6666665459E-1f;
  y = y * x + 5.0000001201E-1f;
  y = y * z + x + 1.0f;
  return y * std::bit_cast<float>(static_cast<std::uint32_t>(n + 127) << 23);
}

/// x^p for x >= 0, p >= 0, with 0^0 = 1 (as numpy and the FLIP reference code).
inline float fast_pow(float x, float p) {
  const float r = fast_exp(p * fast_log(x > 0 ? x : 1.0f));
  return x > 0 ? r : (p == 0 ? 1.0f : 0.0f);
}

/// Cube root for a positive normal x.
inline float fast_cbrt(float x) {
  // Dividing the exponent (and mantissa bits) by 3 gives a guess within ~5%;
  // each Newton step squares the relative error.
  float y = std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) / 3u + 709921077u);
  for (int i = 0; i < 3; ++i) y = (2.0f * y + x / (y * y)) * (1.0f / 3.0f);
  return y;
}

}  // namespace terrasprite::quality::detail
