// SPDX-License-Identifier: MIT
// Quadtree LOD levels of a height grid and the grid meshes drawn from them.
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// Sample indices along one axis of n samples for pyramid level k: every
/// 2^k-th sample plus the last one (a narrower last quad when n - 1 is not a
/// multiple of 2^k), so no input size loses data. n >= 1, level >= 0.
std::vector<int> level_indices(int n, int level);

/// Sample indices along one axis for a coarse grid of `quads` quads:
/// round(q * (n - 1) / quads) for q = 0..quads. For n - 1 a multiple of
/// `quads` these are exactly every ((n - 1) / quads)-th sample (the paper's
/// 513 samples, 16 quads: every 32nd). quads is clamped to [1, n - 1].
std::vector<int> quad_indices(int n, int quads);

/// The sample indices along one axis of the grid TerrainGpu draws for
/// `quads`: every sample for quads <= 0 (full resolution), else quad_indices.
std::vector<int> grid_indices(int n, int quads);

/// Number of pyramid levels down to (and including) the first level with
/// at most `min_quads` quads along the longer axis.
int level_count(const Heightfield& h, int min_quads = 1);

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
/// not what a grid draws: the synthetic terrain's 64-quad grid (240 m quads)
/// lies up to tens of metres above it, and a camera walking 1.7 m above the
/// bilinear surface saw the grid from below. Outside the grid: clamped to
/// its border. xs and ys as for build_grid_mesh.
double grid_surface_height(const Heightfield& h, std::span<const int> xs, std::span<const int> ys,
                           double x, double y);

/// grid_surface_height of the grid TerrainGpu draws for `quads`
/// (grid_indices), as a function of world (x, y). Holds `h` by reference:
/// it must outlive the function.
std::function<double(double, double)> grid_surface(const Heightfield& h, int quads);

}  // namespace terrasprite
