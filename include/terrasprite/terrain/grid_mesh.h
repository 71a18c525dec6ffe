// SPDX-License-Identifier: MIT
// Triangle grids over chosen samples of a height grid, and the surface they draw.
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// The sample indices along one axis of the grid TerrainGpu draws for
/// `quads`: every sample for quads <= 0 (full resolution), else quad_indices
/// (terrain/pyramid.h).
std::vector<int> grid_indices(int n, int quads);

/// A triangle grid over the samples picked by xs (columns) and ys (rows).
/// vertices: x, y, z (metres, Heightfield's world frame) and a unit normal
/// from the full-resolution grid, 6 floats each. indices: 2 triangles per
/// quad, counter-clockwise seen from above, one list for one draw call.
struct GridMesh {
  std::vector<float> vertices;
  std::vector<std::uint32_t> indices;
  int columns = 0;  ///< vertices along x
  int rows = 0;     ///< vertices along y
  long long triangles() const { return static_cast<long long>(indices.size() / 3); }
};

/// Builds the mesh; xs and ys must be increasing sample indices (>= 2 each).
GridMesh build_grid_mesh(const Heightfield& h, std::span<const int> xs, std::span<const int> ys);

/// Height in metres of build_grid_mesh(h, xs, ys)'s surface at world (x, y):
/// the plane of the triangle (x, y) falls in, each quad split from its NW to
/// its SE corner as the mesh does. Heightfield::sample's bilinear surface is
/// not what a coarse grid draws (a grid's quads may lie far above or below
/// it), so anything standing on the drawn terrain uses this. Outside the
/// grid: clamped to its border. xs and ys as for build_grid_mesh.
double grid_surface_height(const Heightfield& h, std::span<const int> xs, std::span<const int> ys,
                           double x, double y);

/// grid_surface_height of the grid TerrainGpu draws for `quads`
/// (grid_indices), as a function of world (x, y). Holds `h` by reference:
/// it must outlive the function.
std::function<double(double, double)> grid_surface(const Heightfield& h, int quads);

}  // namespace terrasprite
