// SPDX-License-Identifier: MIT
#include "small_components.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <tuple>

namespace terrasprite::detail {

std::vector<std::uint32_t> without_small_parts(const std::vector<glm::vec3>& positions,
                                               const std::vector<std::uint32_t>& indices,
                                               double max_radius, std::size_t max_removed,
                                               double& removed_radius) {
  removed_radius = 0.0;
  // One id per distinct position among the corners.
  std::map<std::tuple<float, float, float>, std::uint32_t> ids;
  std::vector<std::uint32_t> corner(indices.size());
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const glm::vec3& p = positions[indices[i]];
    corner[i] =
        ids.emplace(std::make_tuple(p.x, p.y, p.z), std::uint32_t(ids.size())).first->second;
  }
  std::vector<std::uint32_t> parent(ids.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t a = find(corner[t]);
    parent[find(corner[t + 1])] = a;
    parent[find(corner[t + 2])] = a;
  }
  struct Part {
    glm::vec3 lo{INFINITY}, hi{-INFINITY};
    std::size_t triangles = 0;
  };
  std::map<std::uint32_t, Part> parts;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    Part& p = parts[find(corner[t])];
    ++p.triangles;
    for (int k = 0; k < 3; ++k) {
      p.lo = glm::min(p.lo, positions[indices[t + k]]);
      p.hi = glm::max(p.hi, positions[indices[t + k]]);
    }
  }
  std::vector<std::pair<double, std::uint32_t>> by_radius;  // (radius, root)
  for (const auto& [root, p] : parts)
    by_radius.emplace_back(0.5 * glm::length(glm::dvec3(p.hi - p.lo)), root);
  std::sort(by_radius.begin(), by_radius.end());
  std::vector<std::uint32_t> gone;  // roots left out
  std::size_t removed = 0;
  // Never every part: a model of equal small parts keeps them all.
  for (std::size_t k = 0; k + 1 < by_radius.size(); ++k) {
    const auto [radius, root] = by_radius[k];
    if (radius > max_radius || removed + parts[root].triangles > max_removed) break;
    removed += parts[root].triangles;
    removed_radius = radius;
    gone.push_back(root);
  }
  if (gone.empty()) return indices;
  std::sort(gone.begin(), gone.end());
  std::vector<std::uint32_t> kept;
  kept.reserve(indices.size() - 3 * removed);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
    if (!std::binary_search(gone.begin(), gone.end(), find(corner[t])))
      kept.insert(kept.end(), {indices[t], indices[t + 1], indices[t + 2]});
  return kept;
}

}  // namespace terrasprite::detail
