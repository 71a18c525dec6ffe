// SPDX-License-Identifier: MIT
// Internal to quality/: branch-free float cbrt, exp, log and pow that GCC can
// vectorise (the libm calls cannot be without -ffast-math, which we do not
// use). Accurate to a few float ulps over the ranges FLIP feeds them:
// exp/log are the Cephes single-precision polynomials (S. L. Moshier), cbrt
// is a bit-level guess refined by three Newton steps.
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace terrasprite::quality::detail {

/// Natural log for x > 0 (finite, normal).
inline float fast_log(float x) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
  float fe = static_cast<float>(static_cast<int>(bits >> 23) - 126);   // x > 0: no sign bit
  float m = std::bit_cast<float>((bits & 0x007fffffu) | 0x3f000000u);  // m in [0.5, 1)
  // Keep m in [sqrt(1/2), sqrt(2)) so the polynomial's argument stays small.
  // (Selects between floats, not branches: the loop stays vectorisable.)
  const bool low = m < 0.707106781186547524f;
  fe = low ? fe - 1.0f : fe;
  m = (low ? m + m : m) - 1.0f;
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
  y += fe * -2.12194440e-4f;
  y += -0.5f * z;
  return m + y + fe * 0.693359375f;
}

/// e^x, x clamped to [-87, 88] (results stay normal floats).
inline float fast_exp(float x) {
  x = std::min(std::max(x, -87.0f), 88.0f);
  const float fx = std::floor(x * 1.44269504088896341f + 0.5f);
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
  return y * std::bit_cast<float>(static_cast<std::uint32_t>(static_cast<int>(fx) + 127) << 23);
}

/// x^p for x >= 0, p >= 0, with 0^0 = 1 (as numpy and the FLIP reference code).
inline float fast_pow(float x, float p) {
  const float r = fast_exp(p * fast_log(x > 0 ? x : 1.0f));
  return x > 0 ? r : (p == 0 ? 1.0f : 0.0f);
}

/// Square root for x >= 0 (0 for 0): x / sqrt(x) from the bit-level guess of
/// 1/sqrt(x) and three Newton steps. std::sqrt would be exact, but GCC keeps an
/// errno branch around it that stops the loop from vectorising.
inline float fast_sqrt(float x) {
  const float xs = x > 1e-30f ? x : 1e-30f;
  float y = std::bit_cast<float>(0x5f3759dfu - (std::bit_cast<std::uint32_t>(xs) >> 1));
  for (int i = 0; i < 3; ++i) y = y * (1.5f - 0.5f * xs * y * y);
  return x > 1e-30f ? xs * y : 0.0f;
}

/// Cube root for a positive normal x.
inline float fast_cbrt(float x) {
  // Dividing the exponent (and mantissa bits) by 3 gives a guess within ~5%;
  // each Newton step squares the relative error.
  // The third is taken in float: a vectorised integer division by 3 is ~10
  // instructions (64-bit multiplies and shuffles), a conversion pair is 3; the
  // lost low bits only move the guess, and the Newton steps converge to the
  // same accuracy (max 1.6e-7 relative over 1e-6 .. 1e6, as before).
  const float third = static_cast<float>(std::bit_cast<std::int32_t>(x)) * (1.0f / 3.0f);
  float y = std::bit_cast<float>(static_cast<std::int32_t>(third) + 709921077);
  for (int i = 0; i < 3; ++i) y = (2.0f * y + x / (y * y)) * (1.0f / 3.0f);
  return y;
}

}  // namespace terrasprite::quality::detail
