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
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Rays [r, n) leave the terrain.
inline void sky_from(std::span<MarchHit> hits, std::size_t r, std::size_t n) {
  for (; r < n; ++r) hits[r] = {kInf, 0};
}

// Where a plane's march stands: level L on major grid line m (a multiple of
// 2^L), the previous sample and the current one; `final` once the current
// sample is the exit point.
struct Cursor {
  int L = 0;
  long m = 0;
  double t_prev = 0, t_cur = 0;
  float h_prev = 0, h_cur = 0;
  bool final = false;
};

}  // namespace

// One vertical plane: its line across the grid (major axis, entry and exit
// distances), the distance span of each level, and the reads of the surface along
// it. Lives for one march_with call; every member is small and inlined.
template <class Reader>
class ColumnMarcher::Plane {
 public:
  Plane(const ColumnMarcher& c, Reader& tiles, double dx, double dy)
      : c_(c), d_(c.d_), tiles_(tiles), gu_(dx / d_.spacing_x), gv_(-dy / d_.spacing_y) {}

  // Clips the plane's line to the grid; false when it misses it.
  bool enter_grid() {
    return clip(c_.eu_, gu_, d_.width - 1) && clip(c_.ev_, gv_, d_.height - 1) &&
           t_exit_ > t_entry_;
  }

  // The major axis, the direction along it, and each level's distance span.
  void orient() {
    mu_ = std::abs(gu_) >= std::abs(gv_);
    em_ = mu_ ? c_.eu_ : c_.ev_;
    en_ = mu_ ? c_.ev_ : c_.eu_;
    gm_ = mu_ ? gu_ : gv_;
    gn_ = mu_ ? gv_ : gu_;
    dir_ = gm_ > 0 ? 1 : -1;
    inv_gm_ = 1.0 / gm_;
    a1_ = em_ + t_exit_ * gm_;
    lift2_ = c_.lift_ * c_.lift_;
    kmax_ = std::min(d_.bound_levels, TileReader::kMaxLevels) - 1;
    // Level L spans distances [lo_L, hi_L) (lo_0 = 0, hi_L = t1 2^L); it
    // morphs towards level L+1 over the upper half of that span.
    for (int L = 0; L <= c_.lmax_ && L < 31; ++L) {
      const double hi = c_.t1_ * double(1 << L), lo = L == 0 ? 0.0 : hi * 0.5;
      mid_[L] = 0.5 * (lo + hi);
      half_[L] = hi - mid_[L];
    }
    sparse_ = d_.sparse_levels > 0;
  }

  // Rays bottom first: each starts where the one below hit.
  void march_rays(std::span<const double> slopes, std::span<MarchHit> hits, double* hit_t) {
    const std::size_t n = slopes.size();
    Cursor c = start();
    std::size_t r = 0;
    while (r < n) {
      const double s = slopes[r];
      const double zc = c_.ez_ + s * c.t_cur;
      if (zc <= c.h_cur) {  // ray r meets the surface in this step
        hits[r] = hit_in_step(c, s, zc, hit_t[r]);
        ++r;
        continue;
      }
      if (c.final) {
        sky_from(hits, r, n);
        break;
      }
      if (skip_empty(c, s)) continue;
      step(c);
    }
  }

  // The hits' colours, apart from the march: its branches do not wait on
  // the colour reads, and these run back to back, four at a time from whole
  // levels (runs of hits on one level that do not blend).
  void colour_hits(std::span<MarchHit> hits, const double* hit_t) {
    const std::size_t n = hits.size();
    for (std::size_t k = 0; k < n;) {
      if (!std::isfinite(hits[k].t)) {
        ++k;
        continue;
      }
      std::size_t e = k + 1;  // colour [k, e) here
      if constexpr (std::is_same_v<Reader, BasicTileReader<true>>) {
        const std::size_t run = unblended_run_end(hits, hit_t, k);
        if (run - k >= 4) {
          e = run;
          k += colour_run(hits, hit_t, k, run);
        }
      }
      for (; k < e; ++k) hits[k].color = color_at(int(hits[k].color), hit_t[k]);
    }
  }

 private:
  bool clip(double e, double g, double hi) {
    if (std::abs(g) < 1e-300) return e >= 0.0 && e <= hi;
    double ta = (0.0 - e) / g, tb = (hi - e) / g;
    t_entry_ = std::max(t_entry_, std::min(ta, tb));
    t_exit_ = std::min(t_exit_, std::max(ta, tb));
    return true;
  }

  double dist2(double t) const { return t * t + lift2_; }

  // Level L's morph weight towards level L+1 at distance t.
  float alpha(int L, double t) const {
    if (!c_.s_.blend || L >= c_.lmax_) return 0.f;
    const double D2 = dist2(t);
    if (D2 <= mid_[L] * mid_[L]) return 0.f;
    return float(std::min(1.0, (std::sqrt(D2) - mid_[L]) / half_[L]));
  }

  int level_at(double t) const {
    int L = 0;
    double D2 = dist2(t);
    while (L < c_.lmax_ && D2 >= (c_.t1_ * double(1 << L)) * (c_.t1_ * double(1 << L))) ++L;
    return L;
  }

  float blend_parent(int L, double i, double j, float h, double t) const {
    float a = alpha(L, t);
    if (a <= 0.f) return h;
    float p = tiles_.bilinear_height(L + 1, i * 0.5, j * 0.5);
    return h + a * (p - h);
  }

  // Height on major grid line m (a multiple of 2^L) at distance t. Always
  // inlined: an out-of-line call would keep the plane's state in memory.
  [[gnu::always_inline]] float height_line(int L, long m, double t) const {
    const double scale = 1.0 / double(1 << L);
    const int mL = int(m >> L);
    const double qL = (en_ + t * gn_) * scale;
    const int nmin = mu_ ? tiles_.height(L) : tiles_.width(L);
    const int nmaj = mu_ ? tiles_.width(L) : tiles_.height(L);
    const int j0 = std::clamp(int(floor_i64(qL)), 0, nmin - 2);
    const int j1 = j0 + 1;
    const int ca = std::min(mL, nmaj - 2);
    const typename Reader::Slot* tb = mu_ ? tiles_.cell(L, ca, j0) : tiles_.cell(L, j0, ca);
    float h;
    if (tb) [[likely]] {  // levels <= coarsest_level carry samples
      const float f = float(std::clamp(qL - j0, 0.0, 1.0));
      const float h0 = mu_ ? tb->height_at(mL, j0) : tb->height_at(j0, mL);
      const float h1 = mu_ ? tb->height_at(mL, j1) : tb->height_at(j1, mL);
      h = h0 + (h1 - h0) * f;
    } else {
      h = mu_ ? tiles_.bilinear_height(L + 1, mL * 0.5, qL * 0.5)
              : tiles_.bilinear_height(L + 1, qL * 0.5, mL * 0.5);
    }
    return mu_ ? blend_parent(L, double(mL), qL, h, t) : blend_parent(L, qL, double(mL), h, t);
  }

  // Height anywhere (entry and exit points).
  float height_point(int L, double t) const {
    const double scale = 1.0 / double(1 << L);
    double i = (c_.eu_ + t * gu_) * scale, j = (c_.ev_ + t * gv_) * scale;
    return blend_parent(L, i, j, tiles_.bilinear_height(L, i, j), t);
  }

  std::uint32_t color_at(int L, double t) const {
    const double scale = 1.0 / double(1 << L);
    const double i = (c_.eu_ + t * gu_) * scale, j = (c_.ev_ + t * gv_) * scale;
    const std::uint32_t col = tiles_.bilinear_color(L, i, j);
    const float a = alpha(L, t);
    if (a <= 0.f) return col;
    const std::uint32_t p = tiles_.bilinear_color(L + 1, i * 0.5, j * 0.5);
    return lerp_packed(col, p, std::uint32_t(a * 256.0f + 0.5f));
  }

  // Sparse fine levels (insets): outside their box the finest level is the
  // base's (sparse_levels); inside it the distance decides alone, so a ray
  // entering the box refines there (any line of level L is one of level L-1).
  int floor_at(double u, double v) const {
    return u >= d_.sparse_x0 && u <= d_.sparse_x1 && v >= d_.sparse_y0 && v <= d_.sparse_y1
               ? 0
               : std::min(d_.sparse_levels, c_.lmax_);
  }

  // Coarsens L on line m where distance t allows it (only on lines of the
  // coarser level), and keeps it within the sparse levels' floor.
  void coarsen(int& L, long m, double t) const {
    while (L < c_.lmax_ && (m & ((2L << L) - 1)) == 0 &&
           dist2(t) >= c_.t1_ * double(1 << L) * c_.t1_ * double(1 << L))
      ++L;
    if (!sparse_) [[likely]]
      return;
    const double q = en_ + t * gn_;
    const int f = mu_ ? floor_at(double(m), q) : floor_at(q, double(m));
    while (L < f && (m & ((2L << L) - 1)) == 0) ++L;
    if (L > f) L = std::min(L, std::max(f, level_at(t)));
  }

  // The current sample on line c.m, or the exit point once the line lies
  // past it (`past_exit`).
  void sample_line(Cursor& c, bool past_exit) const {
    if (past_exit) {
      c.t_cur = t_exit_;
      c.h_cur = height_point(c.L, t_exit_);
      c.final = true;
    } else {
      c.t_cur = (double(c.m) - em_) * inv_gm_;
      c.h_cur = height_line(c.L, c.m, c.t_cur);
    }
  }

  // The entry point as the previous sample, the first aligned line after it
  // as the current one.
  Cursor start() const {
    Cursor c;
    c.L = level_at(t_entry_);
    if (sparse_) c.L = std::max(c.L, floor_at(c_.eu_ + t_entry_ * gu_, c_.ev_ + t_entry_ * gv_));
    const double a0 = em_ + t_entry_ * gm_;
    const double step = double(1 << c.L);
    c.m = dir_ > 0 ? long(std::ceil(std::max(a0, 0.0) / step) * step)
                   : long(std::floor(a0 / step) * step);
    if (dir_ < 0 && c.m < 0) c.m = 0;
    c.t_prev = t_entry_;
    c.h_prev = height_point(c.L, t_entry_);
    sample_line(c, dir_ * (double(c.m) - a1_) > 0.0 ||
                       (dir_ > 0 ? double(c.m) <= a0 - 1e-9 : double(c.m) >= a0 + 1e-9));
    return c;
  }

  // One step along the major axis; coarsens first when this line is on the
  // coarser grid.
  void step(Cursor& c) const {
    c.t_prev = c.t_cur;
    c.h_prev = c.h_cur;
    coarsen(c.L, c.m, c.t_cur);
    c.m += dir_ * (1L << c.L);
    sample_line(c, dir_ * (double(c.m) - a1_) > 0.0);
  }

  // The hit of a ray of slope s between the previous and current samples
  // (zc: the ray's height at the current one), placed by interpolating the
  // gap; its full-precision distance goes to `t_hit`, its level to `color`.
  MarchHit hit_in_step(const Cursor& c, double s, double zc, double& t_hit) const {
    const double gp = c_.ez_ + s * c.t_prev - c.h_prev, gc = zc - c.h_cur;
    if (gp <= 0.0 && c.t_prev == t_entry_ && t_entry_ > 0.0) {
      // Entering the grid's side below its edge: the ray passes under the
      // surface (there are no skirts), as in the GL mesh.
      return {kInf, 0};
    }
    const double f = gp > 0.0 ? gp / (gp - gc) : 0.0;
    const double th = c.t_prev + f * (c.t_cur - c.t_prev);
    t_hit = th;  // its colour after the march (colour_hits)
    return {float(th), std::uint32_t(c.L)};
  }

  // Hierarchical skip: the largest block of 2^k lines starting at c.m that
  // the ray of slope s passes over entirely. True when it skipped one.
  bool skip_empty(Cursor& c, double s) const {
    if (!c_.s_.max_skip || kmax_ < c.L + 2 || (c.m & ((1L << (c.L + 2)) - 1)) != 0) return false;
    for (int k = kmax_; k >= c.L + 2; --k) {
      const long size = 1L << k;
      if ((c.m & (size - 1)) != 0) continue;
      const long me = c.m + dir_ * size;
      if (dir_ * (double(me) - a1_) > 0.0) continue;
      const double tb = (double(me) - em_) * inv_gm_;
      const double zmin = c_.ez_ + s * (s < 0 ? tb : c.t_cur);
      if (zmin > block_bound(k, std::min(c.m, me), en_ + c.t_cur * gn_, en_ + tb * gn_)) {
        c.m = me;
        c.t_cur = tb;
        c.h_cur = height_line(c.L, c.m, c.t_cur);
        c.t_prev = c.t_cur;
        c.h_prev = c.h_cur;
        coarsen(c.L, c.m, c.t_cur);
        return true;
      }
    }
    return false;
  }

  // The highest bound of level k's cells on major line m_lo >> k between
  // minor coordinates qa and qb (level-0 units).
  float block_bound(int k, long m_lo, double qa, double qb) const {
    const double size = double(1L << k);
    const int nmaj = (mu_ ? tiles_.width(k) : tiles_.height(k)) - 1;
    const int nmin = (mu_ ? tiles_.height(k) : tiles_.width(k)) - 1;
    const int ca = std::clamp(int(m_lo >> k), 0, nmaj - 1);
    const int b0 = std::clamp(int(floor_i64(std::min(qa, qb) / size)), 0, nmin - 1);
    const int b1 = std::clamp(int(floor_i64(std::max(qa, qb) / size)), 0, nmin - 1);
    float bound = -std::numeric_limits<float>::infinity();
    const typename Reader::Slot* sl = mu_ ? tiles_.cell(k, ca, b0) : tiles_.cell(k, b0, ca);
    if (sl && unsigned(b1 - (mu_ ? sl->y0 : sl->x0)) < (mu_ ? sl->ch : sl->cw)) [[likely]] {
      for (int b = b0; b <= b1; ++b)  // the whole run in one tile
        bound = std::max(bound, mu_ ? sl->bound_at(ca, b) : sl->bound_at(b, ca));
    } else {
      for (int b = b0; b <= b1; ++b)
        bound = std::max(bound, mu_ ? tiles_.bound(k, ca, b) : tiles_.bound(k, b, ca));
    }
    return bound;
  }

  // The end of the run of hits from k on one level that do not blend.
  std::size_t unblended_run_end(std::span<const MarchHit> hits, const double* hit_t,
                                std::size_t k) const {
    const int Lk = int(hits[k].color);
    std::size_t run = k;
    while (run < hits.size() && std::isfinite(hits[run].t) && int(hits[run].color) == Lk &&
           alpha(Lk, hit_t[run]) <= 0.f)
      ++run;
    return run;
  }

  // Colours hits [k, run) of one whole level four at a time; returns how
  // many it coloured (the rest are the caller's).
  std::size_t colour_run(std::span<MarchHit> hits, const double* hit_t, std::size_t k,
                         std::size_t run) const {
    const int Lk = int(hits[k].color);
    const typename Reader::Slot* sl = tiles_.cell(Lk, 0, 0);
    const LevelColors level{sl->color, sl->off, sl->stride, tiles_.width(Lk), tiles_.height(Lk)};
    const HitLine line{c_.eu_, c_.ev_, gu_, gv_, 1.0 / double(1 << Lk)};
    return hit_colors(level, line, hit_t + k, hits.data() + k, run - k);
  }

  const ColumnMarcher& c_;
  const TerrainGrid& d_;
  Reader& tiles_;
  const double gu_, gv_;  // grid units per horizontal metre along the plane
  double t_entry_ = 0.0, t_exit_ = std::numeric_limits<double>::infinity();  // entry, exit (metres)
  bool mu_ = true;                            // the major axis is u (columns)
  double em_ = 0, en_ = 0, gm_ = 0, gn_ = 0;  // eye and direction, major and minor axes
  int dir_ = 1;                               // the major coordinate's sign along the plane
  double inv_gm_ = 0, a1_ = 0;                // 1 / gm, the major coordinate at the exit
  double lift2_ = 0;
  int kmax_ = 0;               // the coarsest bound level a skip reads
  double mid_[32], half_[32];  // each level's morph span (set by orient)
  bool sparse_ = false;
};

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
  // Whole levels need no per-read tile check.
  if (whole_)
    march_with<BasicTileReader<true>>(dx, dy, slopes, hits);
  else
    march_with<TileReader>(dx, dy, slopes, hits);
}

template <class Reader>
void ColumnMarcher::march_with(double dx, double dy, std::span<const double> slopes,
                               std::span<MarchHit> hits) const {
  const std::size_t n = slopes.size();
  if (!d_.has_area()) return sky_from(hits, 0, n);
  Reader tiles(src_);
  thread_local std::vector<double> hit_t_store;  // each hit's distance, full precision
  if (hit_t_store.size() < n) hit_t_store.resize(n);
  double* const hit_t = hit_t_store.data();

  Plane<Reader> plane(*this, tiles, dx, dy);
  if (!plane.enter_grid()) return sky_from(hits, 0, n);
  plane.orient();
  plane.march_rays(slopes, hits, hit_t);
  plane.colour_hits(hits.first(n), hit_t);
}

}  // namespace terrasprite
