// SPDX-License-Identifier: MIT
// LOD chain by successive simplification (Garland-Heckbert quadrics as
// implemented by meshoptimizer 0.18: meshopt_simplify, meshopt_simplifySloppy).
#include "terrasprite/objects/lod_chain.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <unordered_map>

#include "sloppy_groups.h"
#include "small_components.h"

namespace terrasprite {
namespace {

// The model's triangles on vertices welded by (position, uv, material).
struct Welded {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;
  std::vector<int> material;
  std::vector<std::uint32_t> indices;
};

Welded weld(const Model& m) {
  std::vector<int> vertex_material(m.vertices(), 0);
  for (const MeshPart& p : m.parts)
    for (std::uint32_t i = p.first_index; i < p.first_index + p.index_count; ++i)
      vertex_material[m.indices[i]] = p.material;
  const meshopt_Stream streams[] = {{m.positions.data(), sizeof(glm::vec3), sizeof(glm::vec3)},
                                    {m.uvs.data(), sizeof(glm::vec2), sizeof(glm::vec2)},
                                    {vertex_material.data(), sizeof(int), sizeof(int)}};
  std::vector<unsigned> remap(m.vertices());
  const std::size_t n = meshopt_generateVertexRemapMulti(
      remap.data(), m.indices.data(), m.indices.size(), m.vertices(), streams, 3);
  Welded w;
  w.positions.resize(n);
  w.uvs.resize(n);
  w.material.resize(n);
  meshopt_remapVertexBuffer(w.positions.data(), m.positions.data(), m.vertices(), sizeof(glm::vec3),
                            remap.data());
  meshopt_remapVertexBuffer(w.uvs.data(), m.uvs.data(), m.vertices(), sizeof(glm::vec2),
                            remap.data());
  meshopt_remapVertexBuffer(w.material.data(), vertex_material.data(), m.vertices(), sizeof(int),
                            remap.data());
  w.indices.resize(m.indices.size());
  meshopt_remapIndexBuffer(w.indices.data(), m.indices.data(), m.indices.size(), remap.data());
  return w;
}

// Per-corner normals: area-weighted faces around the corner's position whose
// normal is within the crease angle of the corner's own face.
std::vector<glm::vec3> crease_normals(const Welded& w, const std::vector<std::uint32_t>& idx,
                                      double crease_deg) {
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> faces_at;  // position -> triangles
  auto key = [&](std::uint32_t v) {
    const glm::vec3 p = w.positions[v];
    std::uint64_t h = 1469598103934665603ull;
    for (float f : {p.x, p.y, p.z}) {
      std::uint32_t b;
      std::memcpy(&b, &f, 4);
      h = (h ^ b) * 1099511628211ull;
    }
    return h;
  };
  const std::size_t tris = idx.size() / 3;
  std::vector<glm::dvec3> face(tris);
  for (std::size_t t = 0; t < tris; ++t) {
    const glm::dvec3 a(w.positions[idx[3 * t]]), b(w.positions[idx[3 * t + 1]]),
        c(w.positions[idx[3 * t + 2]]);
    face[t] = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k) faces_at[key(idx[3 * t + k])].push_back(std::uint32_t(t));
  }
  const double cos_crease = std::cos(crease_deg * 3.14159265358979 / 180.0);
  std::vector<glm::vec3> out(idx.size());
  for (std::size_t t = 0; t < tris; ++t) {
    const glm::dvec3 own = glm::length(face[t]) > 0 ? glm::normalize(face[t]) : glm::dvec3(0, 0, 1);
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 sum(0.0);
      for (std::uint32_t f : faces_at[key(idx[3 * t + k])]) {
        const double len = glm::length(face[f]);
        if (len > 0 && glm::dot(face[f] / len, own) >= cos_crease) sum += face[f];
      }
      out[3 * t + k] = glm::vec3(glm::length(sum) > 0 ? glm::normalize(sum) : own);
    }
  }
  return out;
}

// A level from welded vertices and a simplified index list: triangles grouped
// by material, normals, unused vertices dropped, cache and fetch optimised.
LodLevel make_level(const Welded& w, std::vector<std::uint32_t> idx, bool crease,
                    double crease_deg) {
  const std::size_t tris = idx.size() / 3;
  std::vector<std::uint32_t> order(tris);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return w.material[idx[3 * a]] < w.material[idx[3 * b]];
  });
  std::vector<std::uint32_t> sorted(idx.size());
  for (std::size_t t = 0; t < tris; ++t)
    for (int k = 0; k < 3; ++k) sorted[3 * t + k] = idx[3 * order[t] + k];
  // Unindexed corners, then welded again by (position, normal, uv, material).
  LodLevel lv;
  std::vector<glm::vec3> cp(sorted.size()), cn;
  std::vector<glm::vec2> cu(sorted.size());
  std::vector<int> cm(sorted.size());
  for (std::size_t c = 0; c < sorted.size(); ++c) {
    cp[c] = w.positions[sorted[c]];
    cu[c] = w.uvs[sorted[c]];
    cm[c] = w.material[sorted[c]];
  }
  std::vector<std::uint32_t> identity(sorted.size());
  std::iota(identity.begin(), identity.end(), 0u);
  cn = crease ? crease_normals(w, sorted, crease_deg) : smooth_normals(cp, identity);
  for (std::size_t c = 0; c < sorted.size(); c += 3) cm[c + 1] = cm[c + 2] = cm[c];
  const meshopt_Stream streams[] = {
      {cp.data(), 12, 12}, {cn.data(), 12, 12}, {cu.data(), 8, 8}, {cm.data(), 4, 4}};
  std::vector<unsigned> remap(sorted.size());
  const std::size_t n = meshopt_generateVertexRemapMulti(remap.data(), nullptr, sorted.size(),
                                                         sorted.size(), streams, 4);
  lv.positions.resize(n);
  lv.normals.resize(n);
  lv.uvs.resize(n);
  meshopt_remapVertexBuffer(lv.positions.data(), cp.data(), cp.size(), 12, remap.data());
  meshopt_remapVertexBuffer(lv.normals.data(), cn.data(), cn.size(), 12, remap.data());
  meshopt_remapVertexBuffer(lv.uvs.data(), cu.data(), cu.size(), 8, remap.data());
  lv.indices.resize(sorted.size());
  meshopt_remapIndexBuffer(lv.indices.data(), nullptr, sorted.size(), remap.data());
  for (std::size_t t = 0; t < tris; ++t) {
    const int mat = cm[3 * t];
    if (lv.parts.empty() || lv.parts.back().material != mat)
      lv.parts.push_back({std::uint32_t(3 * t), 0, mat});
    lv.parts.back().index_count += 3;
  }
  for (const MeshPart& p : lv.parts)
    meshopt_optimizeVertexCache(lv.indices.data() + p.first_index,
                                lv.indices.data() + p.first_index, p.index_count, n);
  std::vector<unsigned> fetch(n);
  const std::size_t used =
      meshopt_optimizeVertexFetchRemap(fetch.data(), lv.indices.data(), lv.indices.size(), n);
  meshopt_remapIndexBuffer(lv.indices.data(), lv.indices.data(), lv.indices.size(), fetch.data());
  auto apply = [&](auto& v) {
    auto src = v;
    meshopt_remapVertexBuffer(v.data(), src.data(), n, sizeof(v[0]), fetch.data());
    v.resize(used);
  };
  apply(lv.positions);
  apply(lv.normals);
  apply(lv.uvs);
  return lv;
}

// Level 0: the model as loaded, optimised for the vertex cache and fetch.
LodLevel full_level(const Model& m) {
  LodLevel lv{m.positions, m.normals, m.uvs, m.indices, m.parts, 0.0, false};
  for (const MeshPart& p : lv.parts)
    meshopt_optimizeVertexCache(lv.indices.data() + p.first_index,
                                lv.indices.data() + p.first_index, p.index_count, m.vertices());
  std::vector<unsigned> fetch(m.vertices());
  const std::size_t used = meshopt_optimizeVertexFetchRemap(fetch.data(), lv.indices.data(),
                                                            lv.indices.size(), m.vertices());
  meshopt_remapIndexBuffer(lv.indices.data(), lv.indices.data(), lv.indices.size(), fetch.data());
  auto apply = [&](auto& v) {
    auto src = v;
    meshopt_remapVertexBuffer(v.data(), src.data(), src.size(), sizeof(v[0]), fetch.data());
    v.resize(used);
  };
  apply(lv.positions);
  apply(lv.normals);
  apply(lv.uvs);
  return lv;
}

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
glm::dvec3 closest_on_triangle(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Up to kProbes vertices of the full model, always including its extremes
// along each axis (so a lost protrusion is seen).
constexpr std::size_t kProbes = 1024;
constexpr std::size_t kMeasureMaxTriangles = 4096;
// Small parts: at most this fraction of the model's radius (half its bounding
// box's diagonal): pebbles and stones strewn over a model, not its parts.
constexpr double kSmallPart = 0.05;

std::vector<glm::dvec3> probes(const Model& m) {
  std::vector<glm::dvec3> out;
  const std::size_t step = std::max<std::size_t>(1, m.indices.size() / kProbes);
  for (std::size_t i = 0; i < m.indices.size(); i += step)
    out.emplace_back(m.positions[m.indices[i]]);
  for (int k = 0; k < 3; ++k) {
    auto [lo, hi] = std::minmax_element(
        m.indices.begin(), m.indices.end(),
        [&](std::uint32_t a, std::uint32_t b) { return m.positions[a][k] < m.positions[b][k]; });
    out.emplace_back(m.positions[*lo]);
    out.emplace_back(m.positions[*hi]);
  }
  return out;
}

// Largest distance from the probes to the level's surface (one-sided Hausdorff).
double measured_deviation(const std::vector<glm::dvec3>& pts,
                          const std::vector<glm::vec3>& positions,
                          const std::vector<std::uint32_t>& indices) {
  double worst = 0.0;
  for (const glm::dvec3& p : pts) {
    double best = INFINITY;
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
      const glm::dvec3 q = closest_on_triangle(p, glm::dvec3(positions[indices[t]]),
                                               glm::dvec3(positions[indices[t + 1]]),
                                               glm::dvec3(positions[indices[t + 2]]));
      best = std::min(best, glm::dot(p - q, p - q));
    }
    worst = std::max(worst, best);
  }
  return std::sqrt(worst);
}

}  // namespace

std::vector<LodLevel> build_lod_chain(const Model& model, const LodOptions& o) {
  std::vector<LodLevel> chain;
  chain.push_back(full_level(model));
  const Welded w = weld(model);
  const float scale =
      meshopt_simplifyScale(&w.positions[0].x, w.positions.size(), sizeof(glm::vec3));
  const std::size_t full = model.triangles();
  const std::size_t floor_tris =
      std::max<std::size_t>(o.min_triangles, std::size_t(std::ceil(full * o.min_fraction)));
  std::vector<std::uint32_t> current = w.indices;
  double error_m = 0.0;
  bool sloppy = false;
  std::vector<glm::dvec3> probe;
  std::vector<std::uint32_t> region;  // colour region per welded vertex, for sloppy steps
  // meshoptimizer's quadric error misses dropped protrusions (sloppy levels
  // most of all): coarse levels also measure their deviation (on the welded
  // vertices: the level's own are the same points).
  auto level_error = [&](const std::vector<std::uint32_t>& indices, double accumulated) {
    if (indices.size() / 3 > kMeasureMaxTriangles) return accumulated;
    if (probe.empty()) probe = probes(model);
    return std::max(accumulated, measured_deviation(probe, w.positions, indices));
  };
  // One locked-border quadric step of `indices` towards `target_tris` into
  // `out` (sized for the input); returns the indices written.
  auto quadric = [&](const std::vector<std::uint32_t>& indices, std::size_t target_tris,
                     std::vector<std::uint32_t>& out, float& err) {
    return meshopt_simplify(out.data(), indices.data(), indices.size(), &w.positions[0].x,
                            w.positions.size(), sizeof(glm::vec3), target_tris * 3, 1.f,
                            meshopt_SimplifyLockBorder, &err);
  };
  while (current.size() / 3 > floor_tris) {
    const std::size_t target_tris = std::max(floor_tris, std::size_t(current.size() / 3 * o.ratio));
    std::vector<std::uint32_t> next(current.size());
    float err = 0.f;
    std::size_t count = 0;
    if (!sloppy) {
      count = quadric(current, target_tris, next, err);
      sloppy = count > target_tris * 3 * 3 / 2;
    }
    double step_m = double(err) * scale;
    if (sloppy) {
      // Per colour region, so no triangle takes a vertex (uv) of another
      // swatch or island (meshopt_simplifySloppy keeps one vertex per cell).
      if (region.empty()) region = detail::colour_regions(w.uvs, w.material, w.indices);
      next = detail::simplify_sloppy_by_region(w.positions, region, current, target_tris, step_m);
      count = next.size();
    }
    if (count == 0 || count >= current.size()) break;  // cannot shrink further
    next.resize(count);
    double level_m = level_error(next, error_m + step_m);
    if (!sloppy) {
      // Parts no larger than the error this level has anyway, and under
      // kSmallPart of the model's radius, are left out and their triangles
      // go to the rest (small_components.h). The second bound keeps parts
      // that shape the model: at the forest's fourth level (error 1 m) the
      // error bound alone took its tree tops (radius 0.8 m of 7.5).
      double part_m = 0.0;
      const std::vector<std::uint32_t> kept = detail::without_small_parts(
          w.positions, current, std::min(level_m, kSmallPart * model.bounding_radius()),
          current.size() / 3 - next.size() / 3, part_m);
      if (kept.size() < current.size()) {
        std::vector<std::uint32_t> again(kept.size());
        float kept_err = 0.f;
        const std::size_t n = quadric(kept, target_tris, again, kept_err);
        if (n > 0 && n <= count) {
          again.resize(n);
          step_m = std::max(double(kept_err) * scale, part_m);
          level_m = level_error(again, error_m + step_m);
          next = std::move(again);
        }
      }
    }
    error_m = level_m;
    LodLevel lv = make_level(w, next, model.normals_from_file, o.crease_deg);
    lv.error_m = error_m;
    lv.sloppy = sloppy;
    chain.push_back(std::move(lv));
    current = std::move(next);
  }
  return chain;
}

}  // namespace terrasprite
