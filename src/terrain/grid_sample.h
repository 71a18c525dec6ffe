// SPDX-License-Identifier: MIT
// Bilinear sampling of a vertex grid centred on the origin (Heightfield's
// mapping), for grids held in memory and grids computed on demand alike.
#pragma once
#include <algorithm>

namespace terrasprite::detail {

/// The bilinear height at world (x, y) metres of a width x height grid whose
/// sample (i, j) is `at(i, j)`, clamped to the grid (Heightfield::sample).
template <class At>
float sample_grid(int width, int height, double spacing_x, double spacing_y, double x, double y,
                  const At& at) {
  double fi = std::clamp(x / spacing_x + (width - 1) * 0.5, 0.0, double(width - 1));
  double fj = std::clamp((height - 1) * 0.5 - y / spacing_y, 0.0, double(height - 1));
  int i0 = std::min(int(fi), std::max(width - 2, 0)),
      j0 = std::min(int(fj), std::max(height - 2, 0));
  int i1 = std::min(i0 + 1, width - 1), j1 = std::min(j0 + 1, height - 1);
  double a = fi - i0, b = fj - j0;
  double top = at(i0, j0) * (1 - a) + at(i1, j0) * a;
  double bottom = at(i0, j1) * (1 - a) + at(i1, j1) * a;
  return float(top * (1 - b) + bottom * b);
}

}  // namespace terrasprite::detail
