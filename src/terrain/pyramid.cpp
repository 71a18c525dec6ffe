// SPDX-License-Identifier: MIT
// Quadtree LOD levels by down-sampling, as in Chen et al. 1999, section 3.1:
// level k keeps every 2^k-th sample of the full-resolution grid.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "terrasprite/terrain/pyramid.h"

namespace terrasprite {

std::vector<int> level_indices(int n, int level) {
  assert(n >= 1 && level >= 0);
  const int step = 1 << std::min(level, 30);
  std::vector<int> out;
  for (int i = 0; i < n - 1; i += step) out.push_back(i);
  out.push_back(n - 1);
  return out;
}

std::vector<int> quad_indices(int n, int quads) {
  assert(n >= 1);
  if (n == 1) return {0};
  quads = std::clamp(quads, 1, n - 1);
  std::vector<int> out(quads + 1);
  for (int q = 0; q <= quads; ++q) out[q] = int(std::lround(double(q) * (n - 1) / quads));
  return out;
}

int level_count(const Heightfield& h, int min_quads) {
  int levels = 1;
  while (int(level_indices(std::max(h.width, h.height), levels - 1).size()) - 1 > min_quads)
    ++levels;
  return levels;
}

}  // namespace terrasprite
