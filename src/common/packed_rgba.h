// SPDX-License-Identifier: MIT
// RGBA8 packed little-endian in a uint32 (R in the low byte): the lerp that
// the ray caster and the warp share, two channels per multiply.
#pragma once
#include <cstdint>

namespace terrasprite {

/// Lerp of two packed RGBA8 colours, weight f in 0..256 towards b (16-bit
/// lanes cannot overflow: 255 * 256 < 2^16). f = 0 returns a exactly.
inline std::uint32_t lerp_packed(std::uint32_t a, std::uint32_t b, std::uint32_t f) {
  const std::uint32_t g = 256 - f;
  const std::uint32_t rb =
      (((a & 0xff00ffu) * g + (b & 0xff00ffu) * f + 0x800080u) >> 8) & 0xff00ffu;
  const std::uint32_t ga =
      ((((a >> 8) & 0xff00ffu) * g + ((b >> 8) & 0xff00ffu) * f + 0x800080u) >> 8) & 0xff00ffu;
  return rb | (ga << 8);
}

}  // namespace terrasprite
