// SPDX-License-Identifier: MIT
// A double-sided material's triangles that come in pairs on the same three
// positions, wound opposite ways, are a surface's two sides modelled twice.
// Drawn double-sided, both of a pair are set up and rasterised from every
// view and the later one loses the depth test to the earlier; drawn
// single-sided, exactly one of the pair shows from either side. The Kenney
// forest is 756 of its 2006 triangles in such pairs.
#include <algorithm>
#include <array>
#include <cstring>
#include <tuple>
#include <vector>

#include "objects/model_builder.h"

namespace terrasprite::objects {
namespace {

using Corner = std::array<std::uint32_t, 3>;  // a position's float bits

Corner corner(const glm::vec3& p) {
  Corner c;
  std::memcpy(c.data(), &p.x, 4);
  std::memcpy(c.data() + 1, &p.y, 4);
  std::memcpy(c.data() + 2, &p.z, 4);
  return c;
}

/// Triangle `t`'s corners, rotated to start at the least: two triangles on
/// the same positions are wound alike when these are equal, opposite when
/// the second and third are swapped.
std::array<Corner, 3> canonical(const RawModel& raw, std::size_t t) {
  std::array<Corner, 3> c{corner(raw.positions[raw.indices[3 * t]]),
                          corner(raw.positions[raw.indices[3 * t + 1]]),
                          corner(raw.positions[raw.indices[3 * t + 2]])};
  const std::size_t least = c[1] < c[0] ? (c[2] < c[1] ? 2 : 1) : (c[2] < c[0] ? 2 : 0);
  return {c[least], c[(least + 1) % 3], c[(least + 2) % 3]};
}

}  // namespace

std::size_t draw_opposite_twins_single_sided(RawModel& raw) {
  // Per double-sided material, its triangles by the set of their corners:
  // sorted, so that each set's triangles are a run in triangle order (a
  // sort, not a map: several times cheaper on large models).
  struct Entry {
    int material;
    std::array<Corner, 3> corners;  ///< the set: canonical, the last two sorted
    std::size_t triangle;
    auto tie() const { return std::tie(material, corners, triangle); }
  };
  std::vector<Entry> entries;
  for (std::size_t t = 0; t < raw.indices.size() / 3; ++t) {
    const int mat = raw.triangle_material[t];
    if (mat < 0 || std::size_t(mat) >= raw.materials.size() || !raw.materials[mat].double_sided)
      continue;
    const std::array<Corner, 3> wound = canonical(raw, t);
    if (wound[0] == wound[1] || wound[1] == wound[2] || wound[0] == wound[2])
      continue;  // degenerate: no sides
    std::array<Corner, 3> key = wound;
    if (key[2] < key[1]) std::swap(key[1], key[2]);
    entries.push_back({mat, key, t});
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.tie() < b.tie(); });
  std::vector<int> single_of(raw.materials.size(), -1);  // material -> its single-sided copy
  std::size_t paired = 0;
  std::vector<bool> used(entries.size(), false);
  for (std::size_t first = 0, last = 0; first < entries.size(); first = last) {
    while (last < entries.size() && entries[last].material == entries[first].material &&
           entries[last].corners == entries[first].corners)
      ++last;
    // Each triangle with the first later one wound the other way, once
    // (the winding worked out again: few sets hold more than one).
    for (std::size_t i = first; i + 1 < last; ++i) {
      if (used[i]) continue;
      const std::array<Corner, 3> a = canonical(raw, entries[i].triangle);
      for (std::size_t j = i + 1; j < last; ++j) {
        const std::array<Corner, 3> b = canonical(raw, entries[j].triangle);
        if (used[j] || b[1] != a[2] || b[2] != a[1]) continue;
        used[i] = used[j] = true;
        const std::size_t mat = std::size_t(entries[i].material);
        if (single_of[mat] < 0) {
          Material copy = raw.materials[mat];
          copy.name += " (one side each)";
          copy.double_sided = false;
          single_of[mat] = int(raw.materials.size());
          raw.materials.push_back(std::move(copy));
        }
        raw.triangle_material[entries[i].triangle] = raw.triangle_material[entries[j].triangle] =
            single_of[mat];
        paired += 2;
        break;
      }
    }
  }
  return paired;
}

}  // namespace terrasprite::objects
