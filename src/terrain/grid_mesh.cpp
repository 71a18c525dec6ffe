// SPDX-License-Identifier: MIT
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>

#include "terrasprite/terrain/grid_mesh.h"
#include "terrasprite/terrain/pyramid.h"

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

std::vector<int> grid_indices(int n, int quads) {
  return quads <= 0 ? level_indices(n, 0) : quad_indices(n, quads);
}

double grid_surface_height(const Heightfield& h, std::span<const int> xs, std::span<const int> ys,
                           double x, double y) {
  assert(xs.size() >= 2 && ys.size() >= 2);
  // The cell of index coordinate v along `idx`, and where v falls in it (0..1).
  auto locate = [](std::span<const int> idx, double v) {
    v = std::clamp(v, double(idx.front()), double(idx.back()));
    const auto hi = std::upper_bound(idx.begin(), idx.end() - 1, v);
    const std::size_t c = std::size_t(std::max<std::ptrdiff_t>(hi - idx.begin() - 1, 0));
    return std::pair{c, (v - idx[c]) / double(idx[c + 1] - idx[c])};
  };
  const auto [c, u] = locate(xs, x / h.spacing_x + (h.width - 1) * 0.5);
  const auto [r, v] = locate(ys, (h.height - 1) * 0.5 - y / h.spacing_y);   // rows run south
  const double a = h.at(xs[c], ys[r]), b = h.at(xs[c + 1], ys[r]);          // NW, NE
  const double d = h.at(xs[c], ys[r + 1]), e = h.at(xs[c + 1], ys[r + 1]);  // SW, SE
  // Triangles (a, e, b) where u >= v and (a, d, e) where v > u.
  return u >= v ? a + u * (b - a) + v * (e - b) : a + v * (d - a) + u * (e - d);
}

std::function<double(double, double)> grid_surface(const Heightfield& h, int quads) {
  return [&h, xs = grid_indices(h.width, quads), ys = grid_indices(h.height, quads)](
             double x, double y) { return grid_surface_height(h, xs, ys, x, y); };
}

}  // namespace terrasprite
