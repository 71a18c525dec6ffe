// SPDX-License-Identifier: MIT
// The view-dependent coarse mesh: a restricted quadtree refined by
// screen-space error under a triangle budget (see adaptive_mesh.h).
#include "terrasprite/sprite/adaptive_mesh.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <queue>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "terrasprite/terrain/grid_mesh.h"
#include "terrasprite/terrain/pyramid.h"

namespace terrasprite {
namespace {

// Nodes wholly outside the keyframe's view (with a margin) count this much
// of their screen-space error: sprite frames near the keyframe may see them,
// but the keyframe cannot texture them anyway.
constexpr double kOutsideWeight = 0.125;
constexpr double kViewMargin = 0.5;  // of the node's size, on each side

using Key = std::uint64_t;
constexpr int kBits = 28;
constexpr Key kMask = (Key(1) << kBits) - 1;
Key node(int l, int i, int j) {
  return (Key(l) << (2 * kBits)) | (Key(j) << kBits) | Key(i);
}
int level_of(Key k) {
  return int(k >> (2 * kBits));
}
int i_of(Key k) {
  return int(k & kMask);
}
int j_of(Key k) {
  return int((k >> kBits) & kMask);
}
Key parent(Key k) {
  return node(level_of(k) - 1, i_of(k) / 2, j_of(k) / 2);
}
Key child(Key k, int c) {
  return node(level_of(k) + 1, 2 * i_of(k) + (c & 1), 2 * j_of(k) + (c >> 1));
}
// Edge neighbours: east, west, south (rows run south), north.
constexpr std::array<std::array<int, 2>, 4> kDirs{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};

// Height of the two triangles a (NW), b (NE), d (SW), e (SE), diagonal a-e, at (u, v) in [0, 1]^2.
double two_triangles(double za, double zb, double zd, double ze, double u, double v) {
  return v >= u ? za + v * (zd - za) + u * (ze - zd) : za + u * (zb - za) + v * (ze - zb);
}

}  // namespace

struct AdaptiveMesher::Impl {
  const Heightfield& h;
  int levels = 0;
  std::vector<std::vector<int>> xs, ys;  // per level: quad_indices(n, 2^level)
  // Levels below `levels`, row-major: geometric error (monotone), the node's
  // own two-triangle error, height range.
  std::vector<std::vector<float>> error, own, zmin, zmax;

  explicit Impl(const Heightfield& hf) : h(hf) {
    assert(h.width >= 2 && h.height >= 2);
    while ((2 << levels) <= std::min(h.width, h.height) - 1) ++levels;
    for (int l = 0; l <= levels; ++l) {
      xs.push_back(quad_indices(h.width, 1 << l));
      ys.push_back(quad_indices(h.height, 1 << l));
    }
    error.resize(levels);
    own.resize(levels);
    zmin.resize(levels);
    zmax.resize(levels);
    for (int l = levels - 1; l >= 0; --l) {
      const int n = 1 << l;
      error[l].resize(std::size_t(n) * n);
      own[l].resize(std::size_t(n) * n);
      zmin[l].resize(std::size_t(n) * n);
      zmax[l].resize(std::size_t(n) * n);
      tbb::parallel_for(0, n, [&, l, n](int j) {
        for (int i = 0; i < n; ++i) {
          const int x0 = xs[l][i], x1 = xs[l][i + 1], y0 = ys[l][j], y1 = ys[l][j + 1];
          const double za = h.at(x0, y0), zb = h.at(x1, y0), zd = h.at(x0, y1), ze = h.at(x1, y1);
          double dev = 0, lo = INFINITY, hi = -INFINITY;
          for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
              const double z = h.at(x, y);
              lo = std::min(lo, z);
              hi = std::max(hi, z);
              const double s = two_triangles(za, zb, zd, ze, double(x - x0) / (x1 - x0),
                                             double(y - y0) / (y1 - y0));
              dev = std::max(dev, std::abs(z - s));
            }
          const std::size_t at = std::size_t(j) * n + i;
          own[l][at] = float(dev);
          if (l + 1 < levels)  // monotone: a node errs at least as much as its children
            for (int c = 0; c < 4; ++c)
              dev = std::max(
                  dev,
                  double(error[l + 1][std::size_t(2 * j + (c >> 1)) * 2 * n + 2 * i + (c & 1)]));
          error[l][at] = float(dev);
          zmin[l][at] = float(lo);
          zmax[l][at] = float(hi);
        }
      });
    }
  }

  struct Refinement;
  class CellWriter;
  /// Largest vertical distance between a sample and the triangles drawn
  /// over cell q (leaf k): a two-triangle leaf's own error, else measured
  /// on its fan.
  double cell_deviation(const CoarseGrid& g, Key k, std::size_t q,
                        const std::vector<glm::ivec2>& vertex_sample) const;
  double screen_error(Key k, const Camera& cam, const glm::dmat4& vp, double pixel) const {
    const int l = level_of(k), i = i_of(k), j = j_of(k), n = 1 << l;
    const std::size_t at = std::size_t(j) * n + i;
    const double e = error[l][at];
    if (e <= 0) return 0;
    const glm::dvec3 lo(h.world_x(xs[l][i]), h.world_y(ys[l][j + 1]), zmin[l][at]),
        hi(h.world_x(xs[l][i + 1]), h.world_y(ys[l][j]), zmax[l][at]);
    const glm::dvec3 p = cam.position;
    const glm::dvec3 gap = glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0));
    const double s = e / std::max(glm::length(gap), cam.near_m) / pixel;
    // Wholly outside one side of the view frustum (box widened by the margin)?
    const glm::dvec3 m = kViewMargin * (hi - lo) * glm::dvec3(1, 1, 0);
    int out[5] = {0, 0, 0, 0, 0};
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner((c & 1) ? hi.x + m.x : lo.x - m.x, (c & 2) ? hi.y + m.y : lo.y - m.y,
                              (c & 4) ? hi.z : lo.z);
      const glm::dvec4 q = vp * glm::dvec4(corner, 1.0);
      out[0] += q.x > q.w;
      out[1] += q.x < -q.w;
      out[2] += q.y > q.w;
      out[3] += q.y < -q.w;
      out[4] += q.w < cam.near_m;
    }
    for (int o : out)
      if (o == 8) return s * kOutsideWeight;
    return s;
  }
};

// One build: the set of split nodes, the exact triangle count, and the
// splits of the refinement in progress (to undo one that breaks the budget).
struct AdaptiveMesher::Impl::Refinement {
  const Impl& m;
  const Camera& cam;
  glm::dmat4 vp;
  double pixel;
  std::unordered_set<Key> split;
  long long triangles = 2;
  std::vector<Key> journal;
  std::priority_queue<std::pair<double, Key>> queue;

  bool in_bounds(int l, int i, int j) const {
    return i >= 0 && j >= 0 && i < (1 << l) && j < (1 << l);
  }
  bool exists(Key k) const { return level_of(k) == 0 || split.count(parent(k)) > 0; }
  bool leaf(Key k) const { return exists(k) && split.count(k) == 0; }
  // Edges of leaf k whose neighbour at its level is split (they take a midpoint).
  int split_edges(Key k) const {
    const int l = level_of(k), i = i_of(k), j = j_of(k);
    int n = 0;
    for (auto [dx, dy] : kDirs)
      if (in_bounds(l, i + dx, j + dy) && split.count(node(l, i + dx, j + dy))) ++n;
    return n;
  }
  int leaf_triangles(Key k) const {
    const int e = split_edges(k);
    return e == 0 ? 2 : 4 + e;
  }
  void push(Key k) {
    if (level_of(k) < m.levels) queue.emplace(m.screen_error(k, cam, vp, pixel), k);
  }
  void make_exist(Key k) {
    if (exists(k)) return;
    make_exist(parent(k));
    split_leaf(parent(k));
  }
  void split_leaf(Key k) {
    const int l = level_of(k), i = i_of(k), j = j_of(k);
    for (auto [dx, dy] : kDirs)  // restricted: edge neighbours at this level first
      if (in_bounds(l, i + dx, j + dy)) make_exist(node(l, i + dx, j + dy));
    std::array<Key, 4> around{};
    int count = 0;
    for (auto [dx, dy] : kDirs)
      if (in_bounds(l, i + dx, j + dy) && leaf(node(l, i + dx, j + dy)))
        around[count++] = node(l, i + dx, j + dy);
    long long before = leaf_triangles(k), after = 0;
    for (int a = 0; a < count; ++a) before += leaf_triangles(around[a]);
    split.insert(k);
    journal.push_back(k);
    for (int c = 0; c < 4; ++c) after += leaf_triangles(child(k, c));
    for (int a = 0; a < count; ++a) after += leaf_triangles(around[a]);
    triangles += after - before;
    for (int c = 0; c < 4; ++c) push(child(k, c));
  }
  /// Splits leaves until the error is within tolerance or the budget is spent.
  void refine(const AdaptiveMeshOptions& o);
  /// The leaves in depth-first order, children in order 0..3.
  std::vector<Key> leaves() const;
  /// Cells around each cell (itself first), for the metric's reprojection:
  /// the leaves under twelve points just outside its border.
  void link_near_cells(const std::unordered_map<Key, int>& cell_of, CoarseGrid& g) const;
  Key leaf_at(double x, double y) const {
    Key k = node(0, 0, 0);
    while (split.count(k)) {
      const int l = level_of(k) + 1, i = 2 * i_of(k), j = 2 * j_of(k);
      k = node(l, i + (x >= m.xs[l][i + 1] ? 1 : 0), j + (y >= m.ys[l][j + 1] ? 1 : 0));
    }
    return k;
  }
};

AdaptiveMesher::AdaptiveMesher(const Heightfield& h) : p_(std::make_unique<Impl>(h)) {}
AdaptiveMesher::~AdaptiveMesher() = default;
int AdaptiveMesher::levels() const {
  return p_->levels;
}

void AdaptiveMesher::Impl::Refinement::refine(const AdaptiveMeshOptions& o) {
  // Largest screen-space error first until the largest left is within
  // tolerance; a split that breaks the triangle budget is undone (a smaller
  // one may still fit).
  push(node(0, 0, 0));
  while (!queue.empty()) {
    const auto [e, k] = queue.top();
    queue.pop();
    if (!leaf(k)) continue;
    if (e <= o.tolerance_px) break;
    const long long before = triangles;
    journal.clear();
    split_leaf(k);
    if (triangles > o.triangle_budget) {
      for (auto it = journal.rbegin(); it != journal.rend(); ++it) split.erase(*it);
      triangles = before;
    }
  }
}

std::vector<Key> AdaptiveMesher::Impl::Refinement::leaves() const {
  std::vector<Key> out;
  for (std::vector<Key> stack{node(0, 0, 0)}; !stack.empty();) {
    const Key k = stack.back();
    stack.pop_back();
    if (split.count(k))
      for (int c = 3; c >= 0; --c) stack.push_back(child(k, c));
    else
      out.push_back(k);
  }
  return out;
}

// The leaves' cells written into a CoarseGrid: vertices shared by sample,
// triangles per cell, and the error metric's sample of each cell.
class AdaptiveMesher::Impl::CellWriter {
 public:
  CellWriter(const Refinement& r, const Heightfield& h, CoarseGrid& g) : r_(r), h_(h), g_(g) {}

  void cell(std::size_t q, Key k) {
    const int l = level_of(k), i = i_of(k), j = j_of(k);
    const auto& xs = r_.m.xs;
    const auto& ys = r_.m.ys;
    const int x0 = xs[l][i], x1 = xs[l][i + 1], y0 = ys[l][j], y1 = ys[l][j + 1];
    g_.cell_rect[q] = {x0, y0, x1, y1};
    g_.weight[q] = double(x1 - x0) * (y1 - y0);
    g_.cell_first.push_back(int(g_.triangles.size()));
    if (r_.split_edges(k) == 0)
      two_triangles_cell(q, x0, y0, x1, y1);
    else
      fan_cell(q, k, x0, y0, x1, y1);
  }

  // Sample (i, j) of every triangle's corners, by vertex index.
  const std::vector<glm::ivec2>& vertex_samples() const { return vertex_sample_; }

 private:
  std::uint32_t vertex(int i, int j) {
    const Key s = Key(j) * Key(h_.width) + Key(i);
    auto [it, fresh] = vertex_of_.try_emplace(s, std::uint32_t(g_.mesh_vertices.size()));
    if (fresh) {
      g_.mesh_vertices.emplace_back(h_.world_x(i), h_.world_y(j), double(h_.at(i, j)));
      vertex_sample_.emplace_back(i, j);
    }
    return it->second;
  }
  glm::dvec3 sample(int i, int j) const {
    return glm::dvec3(h_.world_x(i), h_.world_y(j), double(h_.at(i, j)));
  }

  // A leaf with no split neighbour: two triangles as build_grid_mesh, the
  // metric's sample at its centre.
  void two_triangles_cell(std::size_t q, int x0, int y0, int x1, int y1) {
    const std::uint32_t a = vertex(x0, y0), b = vertex(x1, y0), d = vertex(x0, y1),
                        e = vertex(x1, y1);
    g_.triangles.insert(g_.triangles.end(), {a, d, e, a, e, b});
    const int ci = (x0 + x1) / 2, cj = (y0 + y1) / 2;
    g_.has_centre[q] = (x1 - x0 >= 2 && y1 - y0 >= 2) ? 1 : 0;
    g_.centre[q] = sample(ci, cj);
    g_.edge_offset[q] = signed_edge_offset(g_.centre[q], sample(x0, y0), sample(x1, y1));
    g_.normal[q] = grid_normal(h_, ci, cj);
  }

  // A fan around the centre over the boundary, counter-clockwise seen from
  // above: a, (west), d, (south), e, (east), b, (north); a midpoint on each
  // edge whose neighbour is split.
  void fan_cell(std::size_t q, Key k, int x0, int y0, int x1, int y1) {
    const int l = level_of(k), i = i_of(k), j = j_of(k);
    const std::uint32_t a = vertex(x0, y0), b = vertex(x1, y0), d = vertex(x0, y1),
                        e = vertex(x1, y1);
    const int xm = r_.m.xs[l + 1][2 * i + 1], ym = r_.m.ys[l + 1][2 * j + 1];
    auto has = [&](int dx, int dy) {
      return r_.in_bounds(l, i + dx, j + dy) && r_.split.count(node(l, i + dx, j + dy)) > 0;
    };
    std::vector<std::uint32_t> ring{a};
    if (has(-1, 0)) ring.push_back(vertex(x0, ym));
    ring.push_back(d);
    if (has(0, 1)) ring.push_back(vertex(xm, y1));
    ring.push_back(e);
    if (has(1, 0)) ring.push_back(vertex(x1, ym));
    ring.push_back(b);
    if (has(0, -1)) ring.push_back(vertex(xm, y0));
    const std::uint32_t c = vertex(xm, ym);
    for (std::size_t v = 0; v < ring.size(); ++v)
      g_.triangles.insert(g_.triangles.end(), {c, ring[v], ring[(v + 1) % ring.size()]});
    fan_metric_sample(q, x0, y0, x1, y1, xm, ym);
  }

  // The metric's sample of a fan: of the quarter centres (each on the spoke
  // from its corner to the centre), the one farthest from its spoke.
  void fan_metric_sample(std::size_t q, int x0, int y0, int x1, int y1, int xm, int ym) {
    const std::array<std::array<int, 6>, 4> quarters{{{x0, y0, xm, ym, x0, y0},
                                                      {xm, y0, x1, ym, x1, y0},
                                                      {x0, ym, xm, y1, x0, y1},
                                                      {xm, ym, x1, y1, x1, y1}}};
    g_.has_centre[q] = 0;
    g_.centre[q] = sample(xm, ym);
    double best = -1;
    for (const auto& [qx0, qy0, qx1, qy1, cx, cy] : quarters) {
      if (qx1 - qx0 < 2 || qy1 - qy0 < 2) continue;
      const int si = (qx0 + qx1) / 2, sj = (qy0 + qy1) / 2;
      const double off = signed_edge_offset(sample(si, sj), sample(cx, cy), sample(xm, ym));
      if (std::abs(off) > best) {
        best = std::abs(off);
        g_.has_centre[q] = 1;
        g_.centre[q] = sample(si, sj);
        g_.edge_offset[q] = off;
        g_.normal[q] = grid_normal(h_, si, sj);
      }
    }
  }

  const Refinement& r_;
  const Heightfield& h_;
  CoarseGrid& g_;
  std::unordered_map<Key, std::uint32_t> vertex_of_;  // by sample index j * width + i
  std::vector<glm::ivec2> vertex_sample_;
};

double AdaptiveMesher::Impl::cell_deviation(const CoarseGrid& g, Key k, std::size_t q,
                                            const std::vector<glm::ivec2>& vertex_sample) const {
  const int l = level_of(k);
  if (l < levels && g.cell_first[q + 1] - g.cell_first[q] == 6)
    return own[l][std::size_t(j_of(k)) * (1 << l) + i_of(k)];
  double dev = 0;
  for (int t = g.cell_first[q]; t < g.cell_first[q + 1]; t += 3) {
    const glm::ivec2 p0 = vertex_sample[g.triangles[t]], p1 = vertex_sample[g.triangles[t + 1]],
                     p2 = vertex_sample[g.triangles[t + 2]];
    const double z0 = h.at(p0.x, p0.y), z1 = h.at(p1.x, p1.y), z2 = h.at(p2.x, p2.y);
    const double det = double(p1.x - p0.x) * (p2.y - p0.y) - double(p2.x - p0.x) * (p1.y - p0.y);
    if (det == 0) continue;
    const glm::ivec2 lo = glm::min(p0, glm::min(p1, p2)), hi = glm::max(p0, glm::max(p1, p2));
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        const double u =
            (double(x - p0.x) * (p2.y - p0.y) - double(p2.x - p0.x) * (y - p0.y)) / det;
        const double v =
            (double(p1.x - p0.x) * (y - p0.y) - double(x - p0.x) * (p1.y - p0.y)) / det;
        if (u < -1e-9 || v < -1e-9 || u + v > 1 + 1e-9) continue;
        dev = std::max(dev, std::abs(h.at(x, y) - (z0 + u * (z1 - z0) + v * (z2 - z0))));
      }
  }
  return dev;
}

void AdaptiveMesher::Impl::Refinement::link_near_cells(const std::unordered_map<Key, int>& cell_of,
                                                       CoarseGrid& g) const {
  const Heightfield& h = m.h;
  for (std::size_t q = 0; q < g.cell_rect.size(); ++q) {
    g.near_first.push_back(int(g.near_cells.size()));
    g.near_cells.push_back(int(q));
    const auto [x0, y0, x1, y1] = g.cell_rect[q];
    const double w = x1 - x0, hh = y1 - y0;
    const std::array<std::array<double, 2>, 12> around{{{x0 - 0.5, y0 - 0.5},
                                                        {x0 + 0.25 * w, y0 - 0.5},
                                                        {x0 + 0.75 * w, y0 - 0.5},
                                                        {x1 + 0.5, y0 - 0.5},
                                                        {x1 + 0.5, y0 + 0.25 * hh},
                                                        {x1 + 0.5, y0 + 0.75 * hh},
                                                        {x1 + 0.5, y1 + 0.5},
                                                        {x0 + 0.75 * w, y1 + 0.5},
                                                        {x0 + 0.25 * w, y1 + 0.5},
                                                        {x0 - 0.5, y1 + 0.5},
                                                        {x0 - 0.5, y0 + 0.75 * hh},
                                                        {x0 - 0.5, y0 + 0.25 * hh}}};
    for (const auto& [x, y] : around) {
      if (x < 0 || y < 0 || x > h.width - 1 || y > h.height - 1) continue;
      const int c = cell_of.at(leaf_at(x, y));
      if (std::find(g.near_cells.begin() + g.near_first.back(), g.near_cells.end(), c) ==
          g.near_cells.end())
        g.near_cells.push_back(c);
    }
  }
  g.near_first.push_back(int(g.near_cells.size()));
}

namespace {

// A grid of `n` adaptive cells with every per-cell array sized.
CoarseGrid adaptive_grid(std::size_t n) {
  CoarseGrid g;
  g.adaptive = true;
  g.quads_x = int(n);
  g.quads_y = 1;
  g.centre.resize(n);
  g.has_centre.resize(n);
  g.edge_offset.resize(n);
  g.normal.resize(n);
  g.max_deviation.resize(n);
  g.cell_rect.resize(n);
  g.weight.resize(n);
  return g;
}

}  // namespace

CoarseGrid AdaptiveMesher::build(const Camera& camera, int width, int height,
                                 const AdaptiveMeshOptions& o) const {
  (void)width;
  const Impl& m = *p_;
  Impl::Refinement r{m, camera, camera.view_projection(), camera.pixel_angle(height)};
  r.refine(o);
  const std::vector<Key> leaves = r.leaves();
  const std::size_t n = leaves.size();
  CoarseGrid g = adaptive_grid(n);
  Impl::CellWriter cells(r, m.h, g);
  std::unordered_map<Key, int> cell_of;
  for (std::size_t q = 0; q < n; ++q) {
    cell_of[leaves[q]] = int(q);
    cells.cell(q, leaves[q]);
  }
  g.cell_first.push_back(int(g.triangles.size()));
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t q) {
    g.max_deviation[q] = m.cell_deviation(g, leaves[q], q, cells.vertex_samples());
  });
  r.link_near_cells(cell_of, g);
  g.serial = next_grid_serial();
  return g;
}

}  // namespace terrasprite
