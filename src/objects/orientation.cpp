// SPDX-License-Identifier: MIT
// Whether a mesh may be drawn single-sided: closed, consistently wound,
// facing out (model.h).
#include <glm/glm.hpp>
#include <map>
#include <unordered_set>
#include <vector>

#include "terrasprite/objects/model.h"

namespace terrasprite {
namespace {

// Vertices welded by exact position: an OBJ splits a vertex at every UV or
// normal seam, and those copies must count as one for edges to pair.
std::vector<std::uint32_t> weld(const std::vector<glm::vec3>& positions) {
  auto less = [](const glm::vec3& a, const glm::vec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  };
  std::map<glm::vec3, std::uint32_t, decltype(less)> first(less);
  std::vector<std::uint32_t> out(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
    out[i] = first.try_emplace(positions[i], std::uint32_t(first.size())).first->second;
  return out;
}

}  // namespace

bool closed_and_outward(const std::vector<glm::vec3>& positions,
                        const std::vector<std::uint32_t>& indices) {
  const std::vector<std::uint32_t> id = weld(positions);
  auto key = [](std::uint32_t a, std::uint32_t b) { return std::uint64_t(a) << 32 | b; };
  std::unordered_set<std::uint64_t> edges;
  edges.reserve(indices.size());
  double volume6 = 0;  // six times the signed volume (divergence theorem)
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t v[3] = {id[indices[t]], id[indices[t + 1]], id[indices[t + 2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (int k = 0; k < 3; ++k)
      // The same directed edge twice: two faces wound the same way meet
      // there (flipped) or more than two do (non-manifold).
      if (!edges.insert(key(v[k], v[(k + 1) % 3])).second) return false;
    const glm::dvec3 a(positions[indices[t]]), b(positions[indices[t + 1]]),
        c(positions[indices[t + 2]]);
    volume6 += glm::dot(a, glm::cross(b, c));
  }
  if (edges.empty()) return false;
  for (std::uint64_t e : edges)
    if (!edges.count(e << 32 | e >> 32)) return false;  // an open edge
  return volume6 > 0;
}

}  // namespace terrasprite
