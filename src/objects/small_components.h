// SPDX-License-Identifier: MIT
// Leaving out a mesh's small disconnected parts before it is simplified.
// Edge collapses cannot remove a closed part (a pebble stops at about ten
// triangles) and cannot shorten an open one's locked border, so a model
// strewn with small parts (the Kenney forest patch: 28 stones of 18
// triangles, a quarter of it) would keep them whole on its first level and
// take every triangle from its trees.
// meshoptimizer 0.21 has this as meshopt_SimplifyPrune; Debian ships 0.18.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace terrasprite::detail {

/// `indices` (a triangle list into `positions`, in range: not checked)
/// without its smallest connected parts: parts are triangles joined through
/// shared corner positions (not vertex indices, so a uv seam does not split
/// a part), a part's radius is half its bounding box's diagonal (positions'
/// units). Parts go smallest first while their radius is at most
/// `max_radius` and the triangles left out stay at most `max_removed`.
/// Sets `removed_radius` to the largest radius left out (0: none).
std::vector<std::uint32_t> without_small_parts(const std::vector<glm::vec3>& positions,
                                               const std::vector<std::uint32_t>& indices,
                                               double max_radius, std::size_t max_removed,
                                               double& removed_radius);

}  // namespace terrasprite::detail
