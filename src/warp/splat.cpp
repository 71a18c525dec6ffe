// SPDX-License-Identifier: MIT
// The depth warp's forward splat (see splat.h): where each real pixel lands,
// in loops without branches that vectorise, then the depth test per band of
// output rows, each band owned by one task.
#include "warp/splat.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>

#include "common/simd.h"

namespace terrasprite::warp {
namespace {

constexpr std::uint32_t kNowhere = ~0u;
constexpr int kSplatSpan = 256;

// One real row's landing arithmetic, held in locals so the loops below
// vectorise (nothing they store can alias it).
struct RowLanding {
  glm::vec3 base, step, o;
  float mx, my, fx, fy, fw, fh;
  RowLanding(const SplatMap& map, int j, int w, int h)
      : base(map.row_base(j)),
        step(map.step),
        o(map.offset),
        mx(map.mx),
        my(map.my),
        fx(map.fx),
        fy(map.fy),
        fw(float(w)),
        fh(float(h)) {}
  // Real pixel i at depth z: new-image position (x, y), depth qz, and
  // whether it lands in the image. No branches; z = +inf (sky) makes q
  // infinite or NaN, so every test fails.
  bool land(float z, int i, float& x, float& y, float& qz) const {
    const float fi = float(i);
    const float qx = z * (base.x + fi * step.x) + o.x, qy = z * (base.y + fi * step.y) + o.y;
    qz = z * (base.z + fi * step.z) + o.z;
    const float inv = 1.0f / std::max(qz, 1e-3f);
    x = mx + fx * qx * inv;
    y = my - fy * qy * inv;
    return (z < Frame::kSky) & (qz > 1e-3f) & (x >= 0.f) & (y >= 0.f) & (x < fw) & (y < fh);
  }
};

// Where real pixels [i0, i1) of row j land: the output pixel index (or
// kNowhere: sky, behind the eye or outside) and depth. No branches, so the
// loop vectorises; the depth test is the caller's.
TS_CLONES_AVX2
void land_span(const SplatMap& map, const float* __restrict depth, int i0, int i1, int j, int w,
               int h, std::uint32_t* __restrict target, float* __restrict zt) {
  const RowLanding row(map, j, w, h);
  for (int i = i0; i < i1; ++i) {
    float x, y, qz;
    const bool in = row.land(depth[i], i, x, y, qz);
    const int xi = int(in ? x : 0.f), yi = int(in ? y : 0.f);
    target[i - i0] = in ? std::uint32_t(yi * w + xi) : kNowhere;
    zt[i - i0] = qz;
  }
}

// The output rows [lo, hi] the real pixels [i0, i1) of row j land in (as
// land_span's, the same arithmetic); lo > hi when none lands. A reduction
// without branches that vectorises.
TS_CLONES_AVX2
void span_rows(const SplatMap& map, const float* __restrict depth, int i0, int i1, int j, int w,
               int h, int& lo, int& hi) {
  const RowLanding row(map, j, w, h);
  int a = h, b = -1;
  for (int i = i0; i < i1; ++i) {
    float x, y, qz;
    const bool in = row.land(depth[i], i, x, y, qz);
    // Out-of-image rows pushed past the ends, so min and max skip them.
    const int lo_i = int(in ? y : row.fh), hi_i = int(in ? y : -1.f);
    a = a < lo_i ? a : lo_i;
    b = b > hi_i ? b : hi_i;
  }
  lo = a;
  hi = b;
}

// Every depth of [d, d + n) is sky (+inf): a reduction that vectorises.
TS_CLONES_AVX2
bool all_sky(const float* __restrict d, int n) {
  int finite = 0;
  for (int i = 0; i < n; ++i) finite |= d[i] < Frame::kSky;
  return finite == 0;
}

// Forward splatting without atomics: the output is cut into bands of rows,
// each owned by one task, so no two threads write one pixel.
//   1. per span of kSplatSpan real pixels, the output rows it lands in;
//   2. per band: its winner slots cleared, then every span that reaches the
//      band landed again, in real-frame order, and each of its pixels that
//      falls in the band kept where it is nearer than the occupant (a tie
//      keeps the earlier, so the winners do not depend on the order).
// The occupant's depth lives in `win_depth` (valid where win holds a key).
constexpr int kSplatBand = 32;

}  // namespace

void splat(const Reference& ref, const SplatMap& map, int w, int h, Warper::Scratch& scratch) {
  const int sw = ref.cam.w, sh = ref.cam.h;
  const int spans = (sw + kSplatSpan - 1) / kSplatSpan;
  std::vector<std::uint32_t>& win = scratch.win;
  std::vector<float>& win_depth = scratch.win_depth;
  std::vector<std::int32_t>& rows = scratch.span_rows;  // lo, hi per span
  win.resize(std::size_t(w) * h);
  win_depth.resize(std::size_t(w) * h);
  rows.resize(std::size_t(sh) * spans * 2);
  const float* depth0 = ref.frame.depth.data();
  tbb::parallel_for(tbb::blocked_range<int>(0, sh, 8), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j < r.end(); ++j)
      for (int s = 0; s < spans; ++s) {
        const int i0 = s * kSplatSpan, i1 = std::min(i0 + kSplatSpan, sw);
        std::int32_t* lohi = rows.data() + (std::size_t(j) * spans + s) * 2;
        const float* depth = depth0 + std::size_t(j) * sw;
        if (all_sky(depth + i0, i1 - i0)) {
          lohi[0] = h;
          lohi[1] = -1;
          continue;
        }
        int lo, hi;
        span_rows(map, depth, i0, i1, j, w, h, lo, hi);
        lohi[0] = lo;
        lohi[1] = hi;
      }
  });
  const int bands = (h + kSplatBand - 1) / kSplatBand;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, bands, 1),
      [&](const tbb::blocked_range<int>& r) {
        std::uint32_t target[kSplatSpan];
        float zt[kSplatSpan];
        for (int band = r.begin(); band < r.end(); ++band) {
          const int y0 = band * kSplatBand, y1 = std::min(y0 + kSplatBand, h);
          const std::uint32_t first = std::uint32_t(y0) * std::uint32_t(w);
          const std::uint32_t size = std::uint32_t(y1 - y0) * std::uint32_t(w);
          std::fill_n(win.data() + first, size, kEmpty);
          for (int j = 0; j < sh; ++j) {
            const float* depth = depth0 + std::size_t(j) * sw;
            for (int s = 0; s < spans; ++s) {
              const std::int32_t* lohi = rows.data() + (std::size_t(j) * spans + s) * 2;
              if (lohi[1] < y0 || lohi[0] >= y1) continue;  // lands elsewhere (or nowhere)
              const int i0 = s * kSplatSpan, i1 = std::min(i0 + kSplatSpan, sw);
              land_span(map, depth, i0, i1, j, w, h, target, zt);
              for (int i = i0; i < i1; ++i) {
                // kNowhere wraps to a huge offset: outside every band.
                const std::uint32_t at = target[i - i0] - first;
                if (at >= size) continue;
                const std::uint32_t t = target[i - i0];
                const float z = zt[i - i0];
                if (win[t] == kEmpty || z < win_depth[t]) {
                  win[t] = pack(i, j);
                  win_depth[t] = z;
                }
              }
            }
          }
        }
      },
      tbb::simple_partitioner());
}

}  // namespace terrasprite::warp
