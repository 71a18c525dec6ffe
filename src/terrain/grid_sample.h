// SPDX-License-Identifier: MIT
// Bilinear sampling of a vertex grid centred on the origin (Heightfield's
// mapping), for grids held in memory and grids computed on demand alike.
#pragma once
#include <algorithm>

namespace terrasprite::detail {

/// `f` clamped to [0, n - 1]; NaN gives 0 (std::clamp passes NaN through,
/// and converting it to an index is undefined).
inline double clamp_grid_coordinate(double f, int n) {
  return f >= 0 ? std::min(f, double(n - 1)) : 0.0;
}

/// The bilinear height at world (x, y) metres of a width x height grid whose
/// sample (i, j) is `at(i, j)`, clamped to the grid (Heightfield::sample). A
/// coordinate that is not finite reads the grid's border: no input indexes
/// outside it.
template <class At>
float sample_grid(int width, int height, double spacing_x, double spacing_y, double x, double y,
                  const At& at) {
  double fi = clamp_grid_coordinate(x / spacing_x + (width - 1) * 0.5, width);
  double fj = clamp_grid_coordinate((height - 1) * 0.5 - y / spacing_y, height);
  int i0 = std::min(int(fi), std::max(width - 2, 0)),
      j0 = std::min(int(fj), std::max(height - 2, 0));
  int i1 = std::min(i0 + 1, width - 1), j1 = std::min(j0 + 1, height - 1);
  double a = fi - i0, b = fj - j0;
  double top = at(i0, j0) * (1 - a) + at(i1, j0) * a;
  double bottom = at(i0, j1) * (1 - a) + at(i1, j1) * a;
  return float(top * (1 - b) + bottom * b);
}

}  // namespace terrasprite::detail
