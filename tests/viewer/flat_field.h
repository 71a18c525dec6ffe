// SPDX-License-Identifier: MIT
// A flat n x n terrain at height z: the viewer tests' ground.
#pragma once
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite::viewer_test {

inline Heightfield flat_field(int n, double spacing, float z) {
  Heightfield h;
  h.width = h.height = n;
  h.spacing_x = h.spacing_y = spacing;
  h.heights.assign(std::size_t(n) * n, z);
  return h;
}

}  // namespace terrasprite::viewer_test
