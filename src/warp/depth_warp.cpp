// SPDX-License-Identifier: MIT
// Per-pixel 3D warping with depth (after Mark, McMillan, Bishop,
// "Post-rendering 3D warping", I3D 1997): forward splatting with a depth test,
// then per output pixel a sub-pixel correction and a bilinear read.
//
//   1. splat: every real-frame pixel goes to the new image at its depth; the
//      nearest one wins each output pixel (a 32-bit slot holding the
//      winner's real pixel). Each task owns a band of output rows, so no
//      two threads write one slot and no atomics are needed.
//   2. resolve: an output pixel with a winner reads the real frame at the
//      winner's position moved by the sub-pixel offset of its landing point.
//      One without (a crack, or a disocclusion) starts from its farthest
//      neighbouring winner and iterates to the real-frame point that lands
//      on it (fixed point); if none does and the pixel sees sky in the real
//      frame, sky; otherwise it is a hole: read from the second reference
//      by the same iteration, or else
//   3. extend the background: along the row, from the farther side.
//
// Speed: both passes work in spans of a row, first a loop without branches
// that vectorises (where each real pixel lands; where each output pixel
// reads, from its winner or, for an empty pixel, from its direction: sky is
// a homography of the rotation alone), then every pixel of the span is
// blended as a winner would be (bilinear_span, across vector lanes). A
// second vectorised pass (classify_span) settles the empty pixels with no
// winner within 2 px whose direction the reference sees as sky; only the
// rest (cracks and silhouettes, which search and iterate, and holes) are
// visited one at a time. The buffers come from the caller's Warper.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>

#include "common/simd.h"
#include "warp/bilinear.h"
#include "warp/crack_search.h"
#include "warp/sky_classify.h"
#include "warp/splat.h"
#include "warp/warp_internal.h"

namespace terrasprite::warp {
namespace {

// Pixels [x0, x1) of output row y: a winner's pixel reads the reference at
// the winner's position moved by its sub-pixel landing offset (as
// Resolver::from_winner); an empty one gets its direction's position in the
// reference (the sky homography), read only if the reference sees sky there.
TS_CLONES_AVX2
void map_span(const SplatMap& map, glm::vec3 dir, glm::vec3 dir_step, const std::uint32_t* keys,
              const float* __restrict ref_depth, int sw, int sh, float kx, float ky, int x0, int x1,
              int y, SpanMap& m) {
  const float py = float(y) + 0.5f, fw = float(sw), fh = float(sh);
  const int n = x1 - x0;
  int ii[kSpan], jj[kSpan], vv[kSpan];
  float zz[kSpan];
  for (int k = 0; k < n; ++k) {
    // kEmpty decodes to (0, 0).
    const std::uint32_t key = keys[x0 + k];
    const std::uint32_t index = key == kEmpty ? 0u : key;
    ii[k] = int(index & ((1u << kIndexBits) - 1));
    jj[k] = int(index >> kIndexBits);
    vv[k] = key != kEmpty;
  }
  for (int k = 0; k < n; ++k) zz[k] = ref_depth[jj[k] * sw + ii[k]];
  // Locals, so nothing in the loop can alias the stores.
  const glm::vec3 b0 = map.base0, bj = map.base_j, bi = map.step, o = map.offset;
  const float mx = map.mx, my = map.my, mfx = map.fx, mfy = map.fy;
  const float smx = map.smx, smy = map.smy, sfx = map.sfx, sfy = map.sfy;
  float* __restrict out_sx = m.sx;
  float* __restrict out_sy = m.sy;
  float* __restrict out_zt = m.zt;
  int* __restrict out_off = m.off;
  std::uint32_t* __restrict out_wx = m.wx;
  std::uint32_t* __restrict out_wy = m.wy;
  std::uint8_t* __restrict out_kind = m.kind;
  std::uint8_t* __restrict out_sky = m.sky;
  for (int k = 0; k < n; ++k) {
    const int valid = vv[k], i = ii[k], j = jj[k];
    const float z = zz[k], fi = float(i), fj = float(j), fx = float(x0 + k);
    const float qx = z * (b0.x + fj * bj.x + fi * bi.x) + o.x;
    const float qy = z * (b0.y + fj * bj.y + fi * bi.y) + o.y;
    const float qz = z * (b0.z + fj * bj.z + fi * bi.z) + o.z;
    const int landed = qz > 1e-3f;
    const float inv = 1.0f / std::max(qz, 1e-3f);  // no division under a condition
    const float lx = mx + mfx * qx * inv, ly = my - mfy * qy * inv;
    const float wsx = fi + 0.5f + (fx + 0.5f - lx) * kx, wsy = fj + 0.5f + (py - ly) * ky;
    const float dx = dir.x + fx * dir_step.x, dy = dir.y + fx * dir_step.y,
                dz = dir.z + fx * dir_step.z;
    const int ahead = dz > 1e-12f;
    const float dinv = 1.0f / std::max(dz, 1e-12f);
    const float ssx = smx + sfx * dx * dinv, ssy = smy - sfy * dy * dinv;
    out_sky[k] = std::uint8_t(ahead & (ssx >= 0.f) & (ssy >= 0.f) & (ssx <= fw) & (ssy <= fh));
    out_kind[k] = std::uint8_t((1 - valid) * kEmptyPixel + valid * (1 - landed) * kSearch);
    const float sx = valid ? wsx : ssx, sy = valid ? wsy : ssy;
    out_sx[k] = sx;
    out_sy[k] = sy;
    out_zt[k] = qz;
    tap(sx, sy, sw, sh, out_off[k], out_wx[k], out_wy[k]);
  }
}

}  // namespace

void warp_depth(const Reference& ref, const Reference* second, const Pinhole& out,
                const WarpOptions& options, WarpedFrame& result, Warper::Scratch& scratch) {
  const SplatMap map(ref.cam, out);
  const SkyMap sky(ref.cam, out);
  splat(ref, map, out.w, out.h, scratch);
  const std::vector<std::uint32_t>& win = scratch.win;
  const Resolver res{ref, second, out, map, win, scratch.win_depth, options.keep_sources, result};
  const int sw = ref.cam.w, sh = ref.cam.h;
  const bool tiny = sw < 2 || sh < 2;  // the block reads need 2 x 2 texels
  const auto* src = reinterpret_cast<const std::uint32_t*>(ref.frame.color.rgba.data());
  const float kx = float(ref.cam.fx / out.fx), ky = float(ref.cam.fy / out.fy);
  tbb::parallel_for(tbb::blocked_range<int>(0, out.h, 4), [&](const tbb::blocked_range<int>& rows) {
    Resolver local = res;
    std::vector<std::uint8_t> column(std::size_t(out.w));      // scratch of near_winners
    std::vector<std::uint8_t> near(std::size_t(out.w));        // a winner within 2 px
    std::vector<std::uint8_t> unresolved(std::size_t(out.w));  // this row's, for extend_background
    SpanMap m;
    std::uint8_t visit[kSpan];
    for (int y = rows.begin(); y < rows.end(); ++y) {
      const std::size_t row = std::size_t(y) * out.w;
      const std::uint32_t* keys = win.data() + row;
      std::uint8_t* miss = unresolved.data();
      // Computed at the row's first span with an empty pixel.
      bool near_done = false;
      glm::vec3 dir, step;
      sky.row(y, dir, step);
      auto* color = reinterpret_cast<std::uint32_t*>(result.frame.color.rgba.data() + row * 4);
      float* depth = result.frame.depth.data() + row;
      std::uint8_t* hole = result.holes.data() + row;
      bool any = false;
      for (int x0 = 0; x0 < out.w; x0 += kSpan) {
        const int x1 = std::min(x0 + kSpan, out.w);
        if (tiny) {
          for (int x = x0; x < x1; ++x) {
            const bool ok =
                (keys[x] != kEmpty && local.winner(keys[x], x, y)) || local.search(x, y);
            miss[x] = !ok;
            any = any || !ok;
          }
          continue;
        }
        map_span(map, dir, step, keys, ref.frame.depth.data(), sw, sh, kx, ky, x0, x1, y, m);
        // Every pixel first as a winner reads (and sky, from its direction):
        // passes without branches; the others are visited below.
        const int n = x1 - x0;
        bilinear_span(src, sw, m.off, m.wx, m.wy, n, color + x0);
        std::memset(hole + x0, 0, std::size_t(n));
        std::memset(miss + x0, 0, std::size_t(n));
        if (options.keep_sources) {
          std::copy_n(m.sx, n, result.source_x.data() + row + x0);
          std::copy_n(m.sy, n, result.source_y.data() + row + x0);
        }
        int others = 0;  // pixels that are not winners
        for (int k = 0; k < n; ++k) others += m.kind[k] != kWinner;
        if (others == 0) {
          std::copy_n(m.zt, n, depth + x0);
          continue;
        }
        if (!near_done) near_winners(win.data(), out.w, out.h, y, column.data(), near.data());
        near_done = true;
        // Many empty pixels (sky): classified across vector lanes; a few
        // (cracks): each tested for sky_direct when visited.
        const bool sparse = others * 8 < n;
        if (sparse) {
          std::copy_n(m.zt, n, depth + x0);
          for (int k = 0; k < n; ++k) visit[k] = m.kind[k] != kWinner;
        } else {
          classify_span(m, near.data() + x0, ref.frame.depth.data(), sw, sh, n, depth + x0, visit);
        }
        for (int k = 0; k < n; ++k) {
          if (!visit[k]) continue;
          const int x = x0 + k;
          if (sparse && sky_direct(m, k, near[std::size_t(x)], ref.frame.depth.data(), sw, sh)) {
            depth[x] = Frame::kSky;
            continue;
          }
          // A search (a winner behind the eye, or a crack: a winner within
          // 2 px), else a hole with no winner nearby.
          const bool ok = m.kind[k] == kSearch || near[std::size_t(x)] ? local.search(x, y)
                                                                       : local.hole(x, y, kEmpty);
          miss[x] = !ok;
          any = any || !ok;
        }
      }
      if (any) extend_background(result, y, miss);
    }
  });
}

}  // namespace terrasprite::warp
