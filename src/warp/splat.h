// SPDX-License-Identifier: MIT
// The depth warp's forward splat (Mark, McMillan, Bishop, "Post-rendering 3D
// warping", I3D 1997, section 3): every real-frame pixel goes to the new image
// at its depth; the nearest one wins each output pixel. A winner is stored as
// its real pixel (a key), one 32-bit slot per output pixel.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "warp/pinhole.h"
#include "warp/warp_internal.h"

namespace terrasprite::warp {

constexpr std::uint32_t kEmpty = ~0u;  // a slot no real pixel landed in

// Real-frame pixel -> new-camera coordinates, linear along a row:
// q = z (row_base(j) + i step) + offset, in the new camera's (right, up, forward).
struct SplatMap {
  glm::vec3 rr, ru, rf, step, offset;
  glm::vec3 base0, base_j;   // row_base(j) = base0 + j base_j
  float mx, my, fx, fy;      // new camera
  float smx, smy, sfx, sfy;  // real camera
  SplatMap(const Pinhole& s, const Pinhole& t) {
    auto in_t = [&](const glm::dvec3& v) {
      return glm::vec3(glm::dot(v, t.r), glm::dot(v, t.u), glm::dot(v, t.f));
    };
    rr = in_t(s.r);
    ru = in_t(s.u);
    rf = in_t(s.f);
    offset = in_t(s.eye - t.eye);
    step = rr / float(s.fx);
    base0 = rf - float((0.5 - s.my) / s.fy) * ru + float((0.5 - s.mx) / s.fx) * rr;
    base_j = -ru / float(s.fy);
    mx = float(t.mx), my = float(t.my), fx = float(t.fx), fy = float(t.fy);
    smx = float(s.mx), smy = float(s.my), sfx = float(s.fx), sfy = float(s.fy);
  }
  glm::vec3 row_base(int j) const { return base0 + float(j) * base_j; }
  // New-camera depth of real pixel (i, j) at depth z: the same arithmetic as
  // land_span's, so the same bits.
  float depth(int i, int j, float z) const {
    const glm::vec3 base = row_base(j);
    return z * (base.z + float(i) * step.z) + offset.z;
  }
  // New-image position (pixel coordinates) and depth of real pixel (i, j) at depth z.
  bool land(int i, int j, float z, float& x, float& y, float& zt) const {
    const glm::vec3 q = z * (row_base(j) + float(i) * step) + offset;
    if (!(q.z > 1e-3f)) return false;
    zt = q.z;
    const float inv = 1.0f / q.z;
    x = mx + fx * q.x * inv;
    y = my - fy * q.y * inv;
    return true;
  }
};

// A winner's key: the real pixel (i, j) as j << 14 | i (both < 16384), so
// decoding needs no division. The nearest wins, ties to the first in row
// order (the smaller key).
constexpr int kIndexBits = 14;

inline std::uint32_t pack(int i, int j) {
  return (std::uint32_t(j) << kIndexBits) | std::uint32_t(i);
}
inline int key_i(std::uint32_t key) {
  return int(key & ((1u << kIndexBits) - 1));
}
inline int key_j(std::uint32_t key) {
  return int(key >> kIndexBits);
}
// The new-camera depth of a (non-empty) key's real pixel.
inline float key_depth(const SplatMap& map, const Reference& ref, std::uint32_t key) {
  const int i = key_i(key), j = key_j(key);
  return map.depth(i, j, ref.frame.depth[std::size_t(j) * ref.cam.w + i]);
}

/// Splats `ref` into scratch.win (w x h winner keys, row-major, kEmpty where
/// none landed) and scratch.win_depth (each winner's new-camera depth, valid
/// where win holds a key). Deterministic: the nearest wins, ties to the
/// smaller key. Parallel over bands of output rows (no atomics).
void splat(const Reference& ref, const SplatMap& map, int w, int h, Warper::Scratch& scratch);

}  // namespace terrasprite::warp
