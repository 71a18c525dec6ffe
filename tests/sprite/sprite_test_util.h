// SPDX-License-Identifier: MIT
// Shared fixtures of the LOD-sprite tests.
#pragma once
#include "terrasprite/camera/camera.h"
#include "terrasprite/terrain/heightfield.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/terrain/synth.h"
#include "terrasprite/terrain/texture_gen.h"

namespace terrasprite::sprite_test {

/// A small, steep synthetic terrain (129² samples at 60 m, 1500 m relief):
/// keyframes come often on a short path.
inline Terrain small_mountains() {
  Terrain t;
  t.heights = synthesize_terrain({.size = 129, .spacing_m = 60.0, .relief_m = 1500.0});
  t.texture = derived_texture(t.heights, 256, 256);
  return t;
}

/// A flat n x n field at `spacing` metres, height 0.
inline Heightfield flat(int n, double spacing) {
  Heightfield h;
  h.width = h.height = n;
  h.spacing_x = h.spacing_y = spacing;
  h.heights.assign(static_cast<std::size_t>(n) * n, 0.f);
  h.name = "flat";
  return h;
}

/// Looking straight down at `above` from `height` metres over it (60 degrees, square).
inline Camera overhead(glm::dvec3 above, double height) {
  Camera c = Camera::look_at(above + glm::dvec3(0, 0, height), above, 60.0, 1.0);
  c.near_m = 1.0;
  c.far_m = 1e5;
  return c;
}

/// PSNR over R, G, B in dB; +inf for identical images.
inline double psnr(const Image& a, const Image& b) {
  return quality::psnr(a.view(), b.view()).rgb;
}

}  // namespace terrasprite::sprite_test
