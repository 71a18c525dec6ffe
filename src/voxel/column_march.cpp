// SPDX-License-Identifier: MIT
// Vertical-plane ray coherence with multiresolution traversal, after Cohen-Or,
// Rich, Lerner, Shenkar, "A real-time photo-realistic visual flythrough"
// (ray casting in a vertical plane, multiresolution traversal), plus
// max-mipmap empty-space skipping for the first hit.
//
//   z ^            ray k+1 starts at ray k's hit: below a height field's
//     |   eye        profile nothing nearer can be hit by a higher ray.
//     |    o-----_____ ray k+1
//     |      `-.___   ''--___
//     |            `-.__  ray k ---> hit
//     |  __/\__/\/\___/ \___/\__  terrain profile in the plane
//     +------------------------------> t (horizontal distance)
//
// Steps are fixed along the major grid axis (one grid line per step), so the
// height at a step is a lerp along the minor axis; a hit is placed between
// two steps by linear interpolation of the gap (sub-voxel accuracy). Level L
// steps 2^L lines and reads level L of the pyramid; the march coarsens only
// on lines of the coarser level ("even steps").
#include "voxel/column_march.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "voxel/hit_colors.h"
#include "voxel/tile_reader.h"

namespace terrasprite {

ColumnMarcher::ColumnMarcher(const TerrainTiles& terrain, const double eye[3],
                             const MarchSettings& settings)
    : src_(terrain), d_(terrain.grid()), s_(settings) {
  eu_ = eye[0] / d_.spacing_x + (d_.width - 1) * 0.5;
  ev_ = (d_.height - 1) * 0.5 - eye[1] / d_.spacing_y;
  ez_ = eye[2];
  lift_ = std::max(0.0, ez_ - double(d_.max_height));
  t1_ = std::min(d_.spacing_x, d_.spacing_y) / std::max(s_.pixel_angle * s_.ratio, 1e-12);
  lmax_ = s_.multires ? std::min(d_.coarsest_level, TileReader::kMaxLevels - 2) : 0;
  whole_ = BasicTileReader<true>::has_whole_levels(terrain);
}

void ColumnMarcher::march(double dx, double dy, std::span<const double> slopes,
                          std::span<MarchHit> hits) const {
  // A per-read tile check cost the in-memory march 5-8 %; whole levels skip it.
  if (whole_)
    march_with<BasicTileReader<true>>(dx, dy, slopes, hits);
  else
    march_with<TileReader>(dx, dy, slopes, hits);
}

template <class Reader>
void ColumnMarcher::march_with(double dx, double dy, std::span<const double> slopes,
                               std::span<MarchHit> hits) const {
  const std::size_t n = slopes.size();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  auto sky_from = [&](std::size_t r) {
    for (; r < n; ++r) hits[r] = {kInf, 0};
  };
  if (!d_.has_area()) return sky_from(0);
  Reader tiles(src_);
  thread_local std::vector<double> hit_t_store;  // each hit's distance, full precision
  if (hit_t_store.size() < n) hit_t_store.resize(n);
  double* const hit_t = hit_t_store.data();

  // Grid units per horizontal metre along the plane.
  const double gu = dx / d_.spacing_x, gv = -dy / d_.spacing_y;
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  auto clip = [&](double e, double g, double hi) {
    if (std::abs(g) < 1e-300) return e >= 0.0 && e <= hi;
    double ta = (0.0 - e) / g, tb = (hi - e) / g;
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
    return true;
  };
  if (!clip(eu_, gu, d_.width - 1) || !clip(ev_, gv, d_.height - 1) || !(t1 > t0))
    return sky_from(0);

  const bool mu = std::abs(gu) >= std::abs(gv);  // major axis is u (columns)
  const double em = mu ? eu_ : ev_, en = mu ? ev_ : eu_;
  const double gm = mu ? gu : gv, gn = mu ? gv : gu;
  const int dir = gm > 0 ? 1 : -1;
  const double inv_gm = 1.0 / gm;
  const double a1 = em + t1 * gm;  // major coordinate at the exit
  const double lift2 = lift_ * lift_;
  const int kmax = std::min(d_.bound_levels, TileReader::kMaxLevels) - 1;

  auto dist2 = [&](double t) { return t * t + lift2; };
  // Level L spans distances [lo_L, hi_L) (lo_0 = 0, hi_L = t1 2^L); it morphs
  // towards level L+1 over the upper half of that span.
  double mid[32], half[32];
  for (int L = 0; L <= lmax_ && L < 31; ++L) {
    const double hi = t1_ * double(1 << L), lo = L == 0 ? 0.0 : hi * 0.5;
    mid[L] = 0.5 * (lo + hi);
    half[L] = hi - mid[L];
  }
  auto alpha = [&](int L, double t) -> float {
    if (!s_.blend || L >= lmax_) return 0.f;
    const double D2 = dist2(t);
    if (D2 <= mid[L] * mid[L]) return 0.f;
    return float(std::min(1.0, (std::sqrt(D2) - mid[L]) / half[L]));
  };
  auto level_at = [&](double t) {
    int L = 0;
    double D2 = dist2(t);
    while (L < lmax_ && D2 >= (t1_ * double(1 << L)) * (t1_ * double(1 << L))) ++L;
    return L;
  };
  auto blend_parent = [&](int L, double i, double j, float h, double t) {
    float a = alpha(L, t);
    if (a <= 0.f) return h;
    float p = tiles.bilinear_height(L + 1, i * 0.5, j * 0.5);
    return h + a * (p - h);
  };
  // Height on major grid line m (a multiple of 2^L) at distance t.
  auto height_line = [&](int L, long m, double t) {
    const double scale = 1.0 / double(1 << L);
    const int mL = int(m >> L);
    const double qL = (en + t * gn) * scale;
    const int nmin = mu ? tiles.height(L) : tiles.width(L);
    const int nmaj = mu ? tiles.width(L) : tiles.height(L);
    const int j0 = std::clamp(int(floor_i64(qL)), 0, nmin - 2);
    const int j1 = j0 + 1;
    const int ca = std::min(mL, nmaj - 2);
    const typename Reader::Slot* tb = mu ? tiles.cell(L, ca, j0) : tiles.cell(L, j0, ca);
    float h;
    if (tb) [[likely]] {  // levels <= coarsest_level carry samples
      const float f = float(std::clamp(qL - j0, 0.0, 1.0));
      const float h0 = mu ? tb->height_at(mL, j0) : tb->height_at(j0, mL);
      const float h1 = mu ? tb->height_at(mL, j1) : tb->height_at(j1, mL);
      h = h0 + (h1 - h0) * f;
    } else {
      h = mu ? tiles.bilinear_height(L + 1, mL * 0.5, qL * 0.5)
             : tiles.bilinear_height(L + 1, qL * 0.5, mL * 0.5);
    }
    return mu ? blend_parent(L, double(mL), qL, h, t) : blend_parent(L, qL, double(mL), h, t);
  };
  // Height anywhere (entry and exit points).
  auto height_point = [&](int L, double t) {
    const double scale = 1.0 / double(1 << L);
    double i = (eu_ + t * gu) * scale, j = (ev_ + t * gv) * scale;
    return blend_parent(L, i, j, tiles.bilinear_height(L, i, j), t);
  };
  auto color_at = [&](int L, double t) {
    const double scale = 1.0 / double(1 << L);
    const double i = (eu_ + t * gu) * scale, j = (ev_ + t * gv) * scale;
    const std::uint32_t c = tiles.bilinear_color(L, i, j);
    const float a = alpha(L, t);
    if (a <= 0.f) return c;
    const std::uint32_t p = tiles.bilinear_color(L + 1, i * 0.5, j * 0.5);
    return lerp_packed(c, p, std::uint32_t(a * 256.0f + 0.5f));
  };

  // Sparse fine levels (insets): outside their box the finest level is the
  // base's (sparse_levels); inside it the distance decides alone, so a ray
  // entering the box refines there (any line of level L is one of level L-1).
  const bool sparse = d_.sparse_levels > 0;
  auto floor_at = [&](double u, double v) {
    return u >= d_.sparse_x0 && u <= d_.sparse_x1 && v >= d_.sparse_y0 && v <= d_.sparse_y1
               ? 0
               : std::min(d_.sparse_levels, lmax_);
  };
  auto coarsen = [&](int& L, long m, double t) {
    while (L < lmax_ && (m & ((2L << L) - 1)) == 0 &&
           dist2(t) >= t1_ * double(1 << L) * t1_ * double(1 << L))
      ++L;
    if (!sparse) [[likely]]
      return;
    const double q = en + t * gn;
    const int f = mu ? floor_at(double(m), q) : floor_at(q, double(m));
    while (L < f && (m & ((2L << L) - 1)) == 0) ++L;
    if (L > f) L = std::min(L, std::max(f, level_at(t)));
  };

  // Start: entry point as the previous sample, first aligned line after it.
  int L = level_at(t0);
  if (sparse) L = std::max(L, floor_at(eu_ + t0 * gu, ev_ + t0 * gv));
  const double a0 = em + t0 * gm;
  long m;
  {
    const double step = double(1 << L);
    m = dir > 0 ? long(std::ceil(std::max(a0, 0.0) / step) * step)
                : long(std::floor(a0 / step) * step);
    if (dir < 0 && m < 0) m = 0;
  }
  double t_prev = t0, t_cur;
  float h_prev = height_point(L, t0), h_cur;
  bool final = false;
  if (dir * (double(m) - a1) > 0.0 || (dir > 0 ? double(m) <= a0 - 1e-9 : double(m) >= a0 + 1e-9)) {
    t_cur = t1;
    h_cur = height_point(L, t1);
    final = true;
  } else {
    t_cur = (double(m) - em) * inv_gm;
    h_cur = height_line(L, m, t_cur);
  }

  std::size_t r = 0;
  while (r < n) {
    const double s = slopes[r];
    const double zc = ez_ + s * t_cur;
    if (zc <= h_cur) {
      const double gp = ez_ + s * t_prev - h_prev, gc = zc - h_cur;
      if (gp <= 0.0 && t_prev == t0 && t0 > 0.0) {
        // Entering the grid's side below its edge: the ray passes under the
        // surface (there are no skirts), as in the GL mesh.
        hits[r++] = {kInf, 0};
        continue;
      }
      const double f = gp > 0.0 ? gp / (gp - gc) : 0.0;
      const double th = t_prev + f * (t_cur - t_prev);
      hit_t[r] = th;  // its colour after the march (below)
      hits[r] = {float(th), std::uint32_t(L)};
      ++r;
      continue;
    }
    if (final) {
      sky_from(r);
      break;
    }
    // Hierarchical skip: a block of 2^k lines the ray passes over entirely.
    if (s_.max_skip && kmax >= L + 2 && (m & ((1L << (L + 2)) - 1)) == 0) {
      bool skipped = false;
      for (int k = kmax; k >= L + 2 && !skipped; --k) {
        const long size = 1L << k;
        if ((m & (size - 1)) != 0) continue;
        const long me = m + dir * size;
        if (dir * (double(me) - a1) > 0.0) continue;
        const double tb = (double(me) - em) * inv_gm;
        const double zmin = ez_ + s * (s < 0 ? tb : t_cur);
        const double qa = en + t_cur * gn, qb = en + tb * gn;
        // Cells of level k.
        const int nmaj = (mu ? tiles.width(k) : tiles.height(k)) - 1;
        const int nmin = (mu ? tiles.height(k) : tiles.width(k)) - 1;
        const int ca = std::clamp(int(std::min(m, me) >> k), 0, nmaj - 1);
        const int b0 = std::clamp(int(floor_i64(std::min(qa, qb) / double(size))), 0, nmin - 1);
        const int b1 = std::clamp(int(floor_i64(std::max(qa, qb) / double(size))), 0, nmin - 1);
        float bound = -std::numeric_limits<float>::infinity();
        const typename Reader::Slot* sl = mu ? tiles.cell(k, ca, b0) : tiles.cell(k, b0, ca);
        if (sl && unsigned(b1 - (mu ? sl->y0 : sl->x0)) < (mu ? sl->ch : sl->cw)) [[likely]] {
          for (int b = b0; b <= b1; ++b)  // the whole run in one tile
            bound = std::max(bound, mu ? sl->bound_at(ca, b) : sl->bound_at(b, ca));
        } else {
          for (int b = b0; b <= b1; ++b)
            bound = std::max(bound, mu ? tiles.bound(k, ca, b) : tiles.bound(k, b, ca));
        }
        if (zmin > bound) {
          m = me;
          t_cur = tb;
          h_cur = height_line(L, m, t_cur);
          t_prev = t_cur;
          h_prev = h_cur;
          skipped = true;
        }
      }
      if (skipped) {
        coarsen(L, m, t_cur);
        continue;
      }
    }
    // One step; coarsen first when this line is on the coarser grid.
    t_prev = t_cur;
    h_prev = h_cur;
    coarsen(L, m, t_cur);
    m += dir * (1L << L);
    if (dir * (double(m) - a1) > 0.0) {
      t_cur = t1;
      h_cur = height_point(L, t1);
      final = true;
    } else {
      t_cur = (double(m) - em) * inv_gm;
      h_cur = height_line(L, m, t_cur);
    }
  }
  // The hits' colours, apart from the march: its branches no longer wait on
  // the colour reads, and these run back to back, four at a time from whole
  // levels (runs of hits on one level that do not blend).
  for (std::size_t k = 0; k < n;) {
    if (!std::isfinite(hits[k].t)) {
      ++k;
      continue;
    }
    const int Lk = int(hits[k].color);
    std::size_t e = k + 1;  // colour [k, e) here
    if constexpr (std::is_same_v<Reader, BasicTileReader<true>>) {
      std::size_t run = k;
      while (run < n && std::isfinite(hits[run].t) && int(hits[run].color) == Lk &&
             alpha(Lk, hit_t[run]) <= 0.f)
        ++run;
      if (run - k >= 4) {
        const typename Reader::Slot* sl = tiles.cell(Lk, 0, 0);
        const LevelColors level{sl->color, sl->off, sl->stride, tiles.width(Lk), tiles.height(Lk)};
        const HitLine line{eu_, ev_, gu, gv, 1.0 / double(1 << Lk)};
        e = run;
        k += hit_colors(level, line, hit_t + k, hits.data() + k, run - k);
      }
    }
    for (; k < e; ++k) hits[k].color = color_at(int(hits[k].color), hit_t[k]);
  }
}

}  // namespace terrasprite
