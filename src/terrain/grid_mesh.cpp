// SPDX-License-Identifier: MIT
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>

#include "terrasprite/terrain_mesh.h"

namespace terrasprite {

GridMesh build_grid_mesh(const Heightfield& h, std::span<const int> xs, std::span<const int> ys) {
  assert(xs.size() >= 2 && ys.size() >= 2);
  GridMesh m;
  m.columns = int(xs.size());
  m.rows = int(ys.size());
  m.vertices.resize(static_cast<std::size_t>(m.columns) * m.rows * 6);
  tbb::parallel_for(0, m.rows, [&](int r) {
    const int j = ys[r];
    for (int c = 0; c < m.columns; ++c) {
      const int i = xs[c];
      // Central differences on the full-resolution grid (one-sided at borders).
      int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, h.width - 1);
      int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, h.height - 1);
      double dzdx = i1 > i0 ? (h.at(i1, j) - h.at(i0, j)) / ((i1 - i0) * h.spacing_x) : 0.0;
      double dzdy = j1 > j0 ? (h.at(i, j0) - h.at(i, j1)) / ((j1 - j0) * h.spacing_y)
                            : 0.0;  // rows run south
      double len = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1.0);
      float* v = &m.vertices[(static_cast<std::size_t>(r) * m.columns + c) * 6];
      v[0] = float(h.world_x(i));
      v[1] = float(h.world_y(j));
      v[2] = h.at(i, j);
      v[3] = float(-dzdx / len);
      v[4] = float(-dzdy / len);
      v[5] = float(1.0 / len);
    }
  });
  m.indices.reserve(static_cast<std::size_t>(m.columns - 1) * (m.rows - 1) * 6);
  for (int r = 0; r + 1 < m.rows; ++r)
    for (int c = 0; c + 1 < m.columns; ++c) {
      std::uint32_t a = r * m.columns + c, b = a + 1, d = a + m.columns, e = d + 1;
      // a=NW, b=NE, d=SW, e=SE; counter-clockwise seen from above.
      m.indices.insert(m.indices.end(), {a, d, e, a, e, b});
    }
  return m;
}

}  // namespace terrasprite
