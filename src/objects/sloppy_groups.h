// SPDX-License-Identifier: MIT
// Sloppy simplification that keeps each triangle's colour: meshopt_simplifySloppy
// moves every vertex of a grid cell onto one representative vertex, whose uv
// may lie in another swatch of a palette atlas (Kenney kits) or another UV
// island. Here the triangles are grouped into colour regions first and each
// region is simplified on its own, so representatives never cross regions.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace terrasprite::detail {

/// The colour region of each vertex of an indexed mesh whose vertices are
/// welded by (position, uv, material): triangles connected through shared
/// vertices form a UV island; islands of one material where one's uv bounding
/// box holds the other's centre (one swatch of an atlas) are one region. Vertices no triangle uses
/// get their own region. `uvs` and `material` have one entry per vertex;
/// indices must be in range (not checked). Regions are numbered 0..n-1.
std::vector<std::uint32_t> colour_regions(const std::vector<glm::vec2>& uvs,
                                          const std::vector<int>& material,
                                          const std::vector<std::uint32_t>& indices);

/// meshopt_simplifySloppy on each region's triangles of `indices` (a triangle's
/// region is its first corner's; all three corners must share it) with a
/// target of `target_triangles` shared in proportion to the regions' triangle
/// counts. A region sloppy would erase is kept whole when it has at most 8
/// triangles and the result still has fewer triangles than `indices`, else it
/// vanishes. Returns the indices
/// (into the same vertex buffer, each triangle's corners in one region) and
/// sets `error_m` to the largest error of a region that kept triangles, in the
/// positions' units (a vanished region's loss is not in it: measure it).
std::vector<std::uint32_t> simplify_sloppy_by_region(const std::vector<glm::vec3>& positions,
                                                     const std::vector<std::uint32_t>& region,
                                                     const std::vector<std::uint32_t>& indices,
                                                     std::size_t target_triangles, double& error_m);

}  // namespace terrasprite::detail
