// SPDX-License-Identifier: MIT
// Shared fixtures of the LOD-sprite tests.
#pragma once
#include "terrasprite/quality.h"
#include "terrasprite/terrain.h"
#include "terrasprite/terrain_gen.h"

namespace terrasprite::sprite_test {

/// A small, steep synthetic terrain (129² samples at 60 m, 1500 m relief):
/// keyframes come often on a short path.
inline Terrain small_mountains() {
  Terrain t;
  t.heights = synthesize_terrain({.size = 129, .spacing_m = 60.0, .relief_m = 1500.0});
  t.texture = derived_texture(t.heights, 256, 256);
  return t;
}

/// PSNR over R, G, B in dB; +inf for identical images.
inline double psnr(const Image& a, const Image& b) {
  return quality::psnr(a.view(), b.view()).rgb;
}

}  // namespace terrasprite::sprite_test
