// SPDX-License-Identifier: MIT
#include "small_components.h"

#include <meshoptimizer.h>

#include <algorithm>

#include "union_find.h"

namespace terrasprite::detail {

std::vector<std::uint32_t> without_small_parts(const std::vector<glm::vec3>& positions,
                                               const std::vector<std::uint32_t>& indices,
                                               double max_radius, std::size_t max_removed,
                                               double& removed_radius) {
  removed_radius = 0.0;
  // Corners at one position share one index, so a uv seam joins its sides.
  std::vector<std::uint32_t> shadow(indices.size());
  meshopt_generateShadowIndexBuffer(shadow.data(), indices.data(), indices.size(), positions.data(),
                                    positions.size(), sizeof(glm::vec3), sizeof(glm::vec3));
  UnionFind parts(positions.size());
  for (std::size_t t = 0; t + 2 < shadow.size(); t += 3) {
    parts.unite(shadow[t], shadow[t + 1]);
    parts.unite(shadow[t], shadow[t + 2]);
  }
  struct Part {
    glm::vec3 lo{INFINITY}, hi{-INFINITY};
    std::size_t triangles = 0;
  };
  std::vector<Part> part(positions.size());  // by root
  for (std::size_t t = 0; t + 2 < shadow.size(); t += 3) {
    Part& p = part[parts.find(shadow[t])];
    ++p.triangles;
    for (int k = 0; k < 3; ++k) {
      p.lo = glm::min(p.lo, positions[indices[t + k]]);
      p.hi = glm::max(p.hi, positions[indices[t + k]]);
    }
  }
  std::vector<std::pair<double, std::uint32_t>> by_radius;  // (radius, root)
  for (std::uint32_t r = 0; r < part.size(); ++r)
    if (part[r].triangles > 0)
      by_radius.emplace_back(0.5 * glm::length(glm::dvec3(part[r].hi - part[r].lo)), r);
  std::sort(by_radius.begin(), by_radius.end());
  std::vector<bool> gone(positions.size(), false);  // by root
  std::size_t removed = 0;
  // Never every part: a model of equal small parts keeps at least its last.
  for (std::size_t k = 0; k + 1 < by_radius.size(); ++k) {
    const auto [radius, root] = by_radius[k];
    if (radius > max_radius || removed + part[root].triangles > max_removed) break;
    removed += part[root].triangles;
    removed_radius = radius;
    gone[root] = true;
  }
  if (removed == 0) return indices;
  std::vector<std::uint32_t> kept;
  kept.reserve(indices.size() - 3 * removed);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
    if (!gone[parts.find(shadow[t])])
      kept.insert(kept.end(), {indices[t], indices[t + 1], indices[t + 2]});
  return kept;
}

}  // namespace terrasprite::detail
