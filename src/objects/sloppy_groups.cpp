// SPDX-License-Identifier: MIT
#include "sloppy_groups.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "union_find.h"

namespace terrasprite::detail {
namespace {

// Regions of at most this many triangles are kept whole rather than erased.
constexpr std::size_t kKeepTriangles = 8;

struct Island {
  std::uint32_t root = 0;
  int material = 0;
  glm::vec2 lo{INFINITY}, hi{-INFINITY};
  bool holds_centre_of(const Island& o) const {
    const glm::vec2 c = 0.5f * (o.lo + o.hi);
    return c.x >= lo.x && c.x <= hi.x && c.y >= lo.y && c.y <= hi.y;
  }
};

}  // namespace

std::vector<std::uint32_t> colour_regions(const std::vector<glm::vec2>& uvs,
                                          const std::vector<int>& material,
                                          const std::vector<std::uint32_t>& indices) {
  const std::size_t n = uvs.size();
  UnionFind uf(n);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    uf.unite(indices[t], indices[t + 1]);
    uf.unite(indices[t], indices[t + 2]);
  }
  // UV islands: their material and uv bounds.
  std::vector<std::int64_t> island_of(n, -1);
  std::vector<Island> islands;
  for (std::uint32_t v : indices) {
    const std::uint32_t r = uf.find(v);
    if (island_of[r] < 0) {
      island_of[r] = std::int64_t(islands.size());
      islands.push_back({r, material[v]});
    }
    Island& is = islands[std::size_t(island_of[r])];
    is.lo = glm::min(is.lo, uvs[v]);
    is.hi = glm::max(is.hi, uvs[v]);
  }
  // Islands of one material where one's uv centre lies in the other's bounds
  // share a colour region (a sweep over u; boxes that merely touch stay apart).
  // Islands with the same bounds (many on one swatch point; a model without
  // uvs) are united first and swept once, so the sweep stays short.
  const auto key = [&](std::size_t i) {
    const Island& is = islands[i];
    return std::make_tuple(is.material, is.lo.x, is.lo.y, is.hi.x, is.hi.y);
  };
  std::vector<std::size_t> order(islands.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  std::vector<std::size_t> unique;
  for (std::size_t i : order) {
    if (!unique.empty() && key(unique.back()) == key(i))
      uf.unite(islands[unique.back()].root, islands[i].root);
    else
      unique.push_back(i);
  }
  for (std::size_t i = 0; i < unique.size(); ++i) {
    const Island& a = islands[unique[i]];
    for (std::size_t j = i + 1; j < unique.size(); ++j) {
      const Island& b = islands[unique[j]];
      if (b.material != a.material || b.lo.x > a.hi.x) break;
      if (a.holds_centre_of(b) || b.holds_centre_of(a)) uf.unite(a.root, b.root);
    }
  }
  std::vector<std::uint32_t> region(n);
  std::vector<std::int64_t> number(n, -1);
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < n; ++v) {
    const std::uint32_t r = uf.find(std::uint32_t(v));
    if (number[r] < 0) number[r] = next++;
    region[v] = std::uint32_t(number[r]);
  }
  return region;
}

std::vector<std::uint32_t> simplify_sloppy_by_region(const std::vector<glm::vec3>& positions,
                                                     const std::vector<std::uint32_t>& region,
                                                     const std::vector<std::uint32_t>& indices,
                                                     std::size_t target_triangles,
                                                     double& error_m) {
  error_m = 0.0;
  const std::size_t tris = indices.size() / 3;
  std::uint32_t regions = 0;
  for (std::uint32_t r : region) regions = std::max(regions, r + 1);
  std::vector<std::vector<std::uint32_t>> by_region(regions);
  for (std::size_t t = 0; t < tris; ++t) {
    std::vector<std::uint32_t>& to = by_region[region[indices[3 * t]]];
    to.insert(to.end(), indices.begin() + std::ptrdiff_t(3 * t),
              indices.begin() + std::ptrdiff_t(3 * t + 3));
  }
  // Each region simplified on its own vertices (so the sloppy grid spans the
  // region): its triangles and error, or unchanged when its share is all.
  struct Result {
    std::vector<std::uint32_t> idx;
    double error_m = 0.0;
    bool vanished = false;
  };
  std::vector<Result> results;
  std::vector<std::int64_t> local_of(positions.size(), -1);
  for (const std::vector<std::uint32_t>& idx : by_region) {
    if (idx.empty()) continue;
    const std::size_t own = idx.size() / 3;
    const auto target = std::size_t(std::llround(double(own) * double(target_triangles) /
                                                 double(std::max<std::size_t>(tris, 1))));
    if (target >= own) {
      results.push_back({idx});
      continue;
    }
    std::vector<std::uint32_t> global, local(idx.size());
    std::vector<glm::vec3> pos;
    for (std::size_t c = 0; c < idx.size(); ++c) {
      if (local_of[idx[c]] < 0) {
        local_of[idx[c]] = std::int64_t(global.size());
        global.push_back(idx[c]);
        pos.push_back(positions[idx[c]]);
      }
      local[c] = std::uint32_t(local_of[idx[c]]);
    }
    for (std::uint32_t g : global) local_of[g] = -1;
    std::vector<std::uint32_t> simplified(idx.size());
    float err = 0.f;
    const std::size_t count =
        meshopt_simplifySloppy(simplified.data(), local.data(), local.size(), &pos[0].x, pos.size(),
                               sizeof(glm::vec3), target * 3, 1.f, &err);
    const float scale = meshopt_simplifyScale(&pos[0].x, pos.size(), sizeof(glm::vec3));
    Result r{{}, double(err) * scale, count == 0};
    for (std::size_t c = 0; c < count; ++c) r.idx.push_back(global[simplified[c]]);
    if (r.vanished) r.idx = idx;  // the region as it was, should it be kept
    results.push_back(std::move(r));
  }
  // Small regions sloppy would erase (a 2-triangle ground quad, a rock) stay
  // as they are while that still leaves fewer triangles than before; else
  // they go. A vanished region's error is left to the caller's measured
  // deviation: its sloppy error (~ its extent) says nothing of how far its
  // surface lies from the regions that remain.
  const auto assemble = [&](bool keep_small) {
    std::vector<std::uint32_t> out;
    error_m = 0.0;
    for (const Result& r : results) {
      if (r.vanished && !(keep_small && r.idx.size() <= 3 * kKeepTriangles)) continue;
      if (!r.vanished) error_m = std::max(error_m, r.error_m);
      out.insert(out.end(), r.idx.begin(), r.idx.end());
    }
    return out;
  };
  std::vector<std::uint32_t> out = assemble(true);
  return out.size() < indices.size() ? out : assemble(false);
}

}  // namespace terrasprite::detail
