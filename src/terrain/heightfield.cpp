// SPDX-License-Identifier: MIT
#include "terrasprite/heightfield.h"

#include <algorithm>
#include <cmath>

namespace terrasprite {

float Heightfield::sample(double x, double y) const {
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

float Heightfield::min_height() const {
  return heights.empty() ? 0.f : *std::min_element(heights.begin(), heights.end());
}

float Heightfield::max_height() const {
  return heights.empty() ? 0.f : *std::max_element(heights.begin(), heights.end());
}

}  // namespace terrasprite
