// SPDX-License-Identifier: MIT
// Nodata filling by AMLE, the absolutely minimizing Lipschitz extension
// (Almansa, Caselles, Haro, Rouge, "Interpolation of digital elevation models
// using AMLE and related methods", IEEE TGRS 40(2), 2002): of all surfaces
// taking the valid cells' values on the void's rim, the one whose steepest
// slope is least, everywhere. So a fill is never steeper than the rim data
// demands (no cliffs where rims of different height meet, unlike a
// rim-inwards or harmonic fill), planes and cone flanks come back exactly, and
// a cut-off peak or crest is capped flat. Discretised with Oberman's
// consistent 8-neighbour scheme (Math. Comp. 74, 2005) and solved coarse to
// fine: each level's solution, interpolated, is the next finer level's first
// guess, relaxed there by Gauss-Seidel sweeps.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/nodata_fill.h"

namespace terrasprite {
namespace {

constexpr int kCoarsestSide = 16;      // a level no larger a side is solved directly
constexpr double kOmega = 1.0;         // relaxation factor (AMLE is nonlinear: no over-relaxation)
constexpr int kSweepsPerLevel = 200;   // most relaxations on a level with a coarse guess
constexpr int kCoarsestSweeps = 4000;  // on the coarsest level (no guess)
constexpr double kTolerance = 1e-5;    // stop when no cell moves more than this x relief

struct Level {
  int w, h;
  std::vector<float> z;
  std::vector<std::uint8_t> fixed;  // 1: a boundary value; 0: to solve for
};

// One cell's AMLE value (Oberman 2005, 8-neighbour stencil): over the pairs of
// neighbours (i, j) at distances d_i, d_j, the one with the steepest slope
// |z_i - z_j| / (d_i + d_j) through the cell, interpolated linearly at the
// cell. Grid edges: only the neighbours inside.
float amle_value(const Level& l, int x, int y) {
  constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1}, kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
  constexpr double kR2 = 1.4142135623730951;
  constexpr double kD[8] = {1, kR2, 1, kR2, 1, kR2, 1, kR2};
  double z[8], d[8];
  int n = 0;
  for (int k = 0; k < 8; ++k) {
    const int nx = x + kDx[k], ny = y + kDy[k];
    if (nx >= 0 && ny >= 0 && nx < l.w && ny < l.h)
      z[n] = l.z[std::size_t(ny) * l.w + nx], d[n++] = kD[k];
  }
  double best = -1, value = l.z[std::size_t(y) * l.w + x];
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double slope = std::abs(z[i] - z[j]) / (d[i] + d[j]);
      if (slope > best) best = slope, value = (d[j] * z[i] + d[i] * z[j]) / (d[i] + d[j]);
    }
  return float(value);
}

void relax(Level& l, const std::vector<int>& holes, int max_sweeps) {
  float lo = 0, hi = 0;
  bool first = true;
  for (std::size_t p = 0; p < l.z.size(); ++p)
    if (l.fixed[p]) {
      lo = first ? l.z[p] : std::min(lo, l.z[p]);
      hi = first ? l.z[p] : std::max(hi, l.z[p]);
      first = false;
    }
  const double tolerance = kTolerance * std::max(1.0, double(hi) - lo) + 1e-6;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    double largest = 0;
    for (int p : holes) {
      const float target = amle_value(l, p % l.w, p / l.w);
      const double step = kOmega * (target - l.z[p]);
      l.z[p] = float(l.z[p] + step);
      largest = std::max(largest, std::abs(step));
    }
    if (largest < tolerance) return;
  }
}

// The next coarser level: a cell is fixed when all of its 2x2 children are
// (their mean is then exact at its centre for a linear surface); when that
// leaves none fixed, when any child is.
Level coarsen(const Level& f, bool all_children) {
  Level c{(f.w + 1) / 2, (f.h + 1) / 2, {}, {}};
  c.z.assign(std::size_t(c.w) * c.h, 0.f);
  c.fixed.assign(c.z.size(), 0);
  for (int y = 0; y < c.h; ++y)
    for (int x = 0; x < c.w; ++x) {
      double sum = 0;
      int n = 0;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const int fx = 2 * x + dx, fy = 2 * y + dy;
          if (fx < f.w && fy < f.h && f.fixed[std::size_t(fy) * f.w + fx])
            sum += f.z[std::size_t(fy) * f.w + fx], ++n;
        }
      const int children = (std::min(2 * x + 2, f.w) - 2 * x) * (std::min(2 * y + 2, f.h) - 2 * y);
      if (n && (!all_children || n == children)) {
        c.z[std::size_t(y) * c.w + x] = float(sum / n);
        c.fixed[std::size_t(y) * c.w + x] = 1;
      }
    }
  return c;
}

// Bilinear value of the solved coarse level at fine cell (x, y).
float prolong(const Level& c, int x, int y) {
  const double cx = std::clamp((x - 0.5) / 2.0, 0.0, c.w - 1.0),
               cy = std::clamp((y - 0.5) / 2.0, 0.0, c.h - 1.0);
  const int x0 = int(cx), y0 = int(cy), x1 = std::min(x0 + 1, c.w - 1),
            y1 = std::min(y0 + 1, c.h - 1);
  const double fx = cx - x0, fy = cy - y0;
  auto at = [&](int i, int j) { return double(c.z[std::size_t(j) * c.w + i]); };
  return float((at(x0, y0) * (1 - fx) + at(x1, y0) * fx) * (1 - fy) +
               (at(x0, y1) * (1 - fx) + at(x1, y1) * fx) * fy);
}

std::vector<int> holes_of(const Level& l) {
  std::vector<int> holes;
  for (int p = 0; p < l.w * l.h; ++p)
    if (!l.fixed[p]) holes.push_back(p);
  return holes;
}

// Solves the level's holes; `l.z` at holes holds a first guess or anything finite.
void solve(Level& l) {
  const std::vector<int> holes = holes_of(l);
  if (holes.empty()) return;
  if (std::max(l.w, l.h) <= kCoarsestSide) {  // max: a 16 x 12304 strip must coarsen too
    relax(l, holes, kCoarsestSweeps);
    return;
  }
  Level c = coarsen(l, true);
  if (std::find(c.fixed.begin(), c.fixed.end(), 1) == c.fixed.end()) c = coarsen(l, false);
  // A coarse hole starts from the mean of the fixed values: any finite start works.
  double mean = 0;
  long long n = 0;
  for (std::size_t p = 0; p < c.z.size(); ++p)
    if (c.fixed[p]) mean += c.z[p], ++n;
  for (std::size_t p = 0; p < c.z.size(); ++p)
    if (!c.fixed[p]) c.z[p] = float(mean / std::max(n, 1LL));
  solve(c);
  for (int p : holes) l.z[p] = prolong(c, p % l.w, p / l.w);
  relax(l, holes, kSweepsPerLevel);
}

}  // namespace

long long fill_nodata(std::span<float> h, std::span<std::uint8_t> valid, int width, int height) {
  Level l{width, height, std::vector<float>(h.begin(), h.end()),
          std::vector<std::uint8_t>(valid.begin(), valid.end())};
  const long long filled = std::count(l.fixed.begin(), l.fixed.end(), 0);
  if (filled == 0) return 0;
  if (filled == static_cast<long long>(width) * height) throw InputError("all cells are nodata");
  solve(l);
  std::copy(l.z.begin(), l.z.end(), h.begin());
  std::fill(valid.begin(), valid.end(), 1);
  return filled;
}

}  // namespace terrasprite
