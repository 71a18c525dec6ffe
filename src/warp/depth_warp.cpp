// SPDX-License-Identifier: MIT
// Per-pixel 3D warping with depth (after Mark, McMillan, Bishop,
// "Post-rendering 3D warping", I3D 1997): forward splatting with a depth test,
// then per output pixel a sub-pixel correction and a bilinear read.
//
//   1. splat: every real-frame pixel goes to the new image at its depth; the
//      nearest one wins each output pixel (a 32-bit atomic slot holding the
//      winner's real pixel; its depth is recomputed to compare).
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
// visited one at a time. The buffers come from the caller's Warper; the
// winner slots are 32 bits (the real pixel, its depth recomputed).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "common/simd.h"
#include "warp/bilinear.h"
#include "warp/warp_internal.h"

namespace terrasprite::warp {
namespace {

constexpr std::uint32_t kEmpty = ~0u;

// Real-frame pixel -> new-camera coordinates, linear along a row:
// q = z (row_base(j) + i step) + offset, in the new camera's (right, up, forward).
struct SplatMap {
  glm::vec3 rr, ru, rf, step, offset;
  glm::vec3 base0, base_j;   // row_base(j) = base0 + j base_j
  float mx, my, fx, fy;      // new camera
  float smx, smy, sfx, sfy;  // real camera
  SplatMap(const Pinhole& s, const Pinhole& t) {
    auto in_t = [&](const glm::dvec3& v) {
      return glm::vec3(glm::dot(v, t.r), glm::dot(v, t.u), glm::dot(v, t.f));
    };
    rr = in_t(s.r);
    ru = in_t(s.u);
    rf = in_t(s.f);
    offset = in_t(s.eye - t.eye);
    step = rr / float(s.fx);
    base0 = rf - float((0.5 - s.my) / s.fy) * ru + float((0.5 - s.mx) / s.fx) * rr;
    base_j = -ru / float(s.fy);
    mx = float(t.mx), my = float(t.my), fx = float(t.fx), fy = float(t.fy);
    smx = float(s.mx), smy = float(s.my), sfx = float(s.fx), sfy = float(s.fy);
  }
  glm::vec3 row_base(int j) const { return base0 + float(j) * base_j; }
  // New-camera depth of real pixel (i, j) at depth z: the same arithmetic as
  // land_span's, so the same bits.
  float depth(int i, int j, float z) const {
    const glm::vec3 base = row_base(j);
    return z * (base.z + float(i) * step.z) + offset.z;
  }
  // New-image position (pixel coordinates) and depth of real pixel (i, j) at depth z.
  bool land(int i, int j, float z, float& x, float& y, float& zt) const {
    const glm::vec3 q = z * (row_base(j) + float(i) * step) + offset;
    if (!(q.z > 1e-3f)) return false;
    zt = q.z;
    const float inv = 1.0f / q.z;
    x = mx + fx * q.x * inv;
    y = my - fy * q.y * inv;
    return true;
  }
};

// A winner's key: the real pixel (i, j) as j << 14 | i (both < 16384), so
// decoding needs no division. The nearest wins, ties to the first in row
// order: (depth bits, key) compared as one 64-bit number, the depth
// recomputed from the reference (SplatMap::depth) rather than stored, which
// halves the buffer.
constexpr int kIndexBits = 14;
// Output pixel -> where its direction (a point at infinity) lies in the
// real frame: a homography of the rotation alone, linear along a row in
// homogeneous coordinates, d = row + x step in the real camera's
// (right, up, forward).
struct SkyMap {
  glm::dvec3 r, u, f;  // output camera's axes in the real camera's frame
  double omx, omy, ofx, ofy;
  float smx, smy, sfx, sfy;
  SkyMap(const Pinhole& s, const Pinhole& t) {
    auto in_s = [&](const glm::dvec3& v) {
      return glm::dvec3(glm::dot(v, s.r), glm::dot(v, s.u), glm::dot(v, s.f));
    };
    r = in_s(t.r), u = in_s(t.u), f = in_s(t.f);
    omx = t.mx, omy = t.my, ofx = t.fx, ofy = t.fy;
    smx = float(s.mx), smy = float(s.my), sfx = float(s.fx), sfy = float(s.fy);
  }
  // Homogeneous direction of output pixel (0.5, y + 0.5) and its step per pixel.
  void row(int y, glm::vec3& base, glm::vec3& step) const {
    const glm::dvec3 b = f + ((0.5 - omx) / ofx) * r - ((y + 0.5 - omy) / ofy) * u;
    base = glm::vec3(b);
    step = glm::vec3(r / ofx);
  }
};

std::uint32_t pack(int i, int j) {
  return (std::uint32_t(j) << kIndexBits) | std::uint32_t(i);
}
int key_i(std::uint32_t key) {
  return int(key & ((1u << kIndexBits) - 1));
}
int key_j(std::uint32_t key) {
  return int(key >> kIndexBits);
}
// Depth and key as one number: the smaller is the winner.
std::uint64_t rank(float depth, std::uint32_t key) {
  return (std::uint64_t(std::bit_cast<std::uint32_t>(depth)) << 32) | key;
}
// The new-camera depth of a (non-empty) key's real pixel.
float key_depth(const SplatMap& map, const Reference& ref, std::uint32_t key) {
  const int i = key_i(key), j = key_j(key);
  return map.depth(i, j, ref.frame.depth[std::size_t(j) * ref.cam.w + i]);
}

// Where real pixels [i0, i1) of row j land: the output pixel index (or
// kNowhere: sky, behind the eye or outside) and depth. No branches, so the
// loop vectorises; the depth test is the caller's.
constexpr std::uint32_t kNowhere = ~0u;
constexpr int kSplatSpan = 256;

TS_CLONES_AVX2
void land_span(const SplatMap& map, const float* __restrict depth, int i0, int i1, int j, int w,
               int h, std::uint32_t* __restrict target, float* __restrict zt) {
  const glm::vec3 base = map.row_base(j), step = map.step, o = map.offset;
  const float mx = map.mx, my = map.my, fx = map.fx, fy = map.fy, fw = float(w), fh = float(h);
  for (int i = i0; i < i1; ++i) {
    const float z = depth[i], fi = float(i);
    const float qx = z * (base.x + fi * step.x) + o.x, qy = z * (base.y + fi * step.y) + o.y;
    const float qz = z * (base.z + fi * step.z) + o.z;
    const float inv = 1.0f / std::max(qz, 1e-3f);
    const float x = mx + fx * qx * inv, y = my - fy * qy * inv;
    // z = +inf (sky) makes q infinite or NaN: every test below fails.
    const bool in =
        (z < Frame::kSky) & (qz > 1e-3f) & (x >= 0.f) & (y >= 0.f) & (x < fw) & (y < fh);
    const int xi = int(in ? x : 0.f), yi = int(in ? y : 0.f);
    target[i - i0] = in ? std::uint32_t(yi * w + xi) : kNowhere;
    zt[i - i0] = qz;
  }
}

// Every depth of [d, d + n) is sky (+inf): a reduction that vectorises.
TS_CLONES_AVX2
bool all_sky(const float* __restrict d, int n) {
  int finite = 0;
  for (int i = 0; i < n; ++i) finite |= d[i] < Frame::kSky;
  return finite == 0;
}

void splat(const Reference& ref, const SplatMap& map, int w, int h,
           std::vector<std::uint32_t>& win) {
  const int sw = ref.cam.w;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, ref.cam.h, 8), [&](const tbb::blocked_range<int>& rows) {
        std::uint32_t target[kSplatSpan];
        float zt[kSplatSpan];
        for (int j = rows.begin(); j < rows.end(); ++j) {
          const float* depth = ref.frame.depth.data() + std::size_t(j) * sw;
          for (int i0 = 0; i0 < sw; i0 += kSplatSpan) {
            const int i1 = std::min(i0 + kSplatSpan, sw);
            if (all_sky(depth + i0, i1 - i0)) continue;  // lands nowhere
            land_span(map, depth, i0, i1, j, w, h, target, zt);
            for (int i = i0; i < i1; ++i) {
              if (target[i - i0] == kNowhere) continue;
              // The nearest wins: an atomic min of rank(depth, key), the
              // occupant's depth recomputed on each try.
              const std::uint32_t key = pack(i, j);
              const std::uint64_t mine = rank(zt[i - i0], key);
              std::atomic_ref<std::uint32_t> slot(win[target[i - i0]]);
              std::uint32_t cur = slot.load(std::memory_order_relaxed);
              while ((cur == kEmpty || mine < rank(key_depth(map, ref, cur), cur)) &&
                     !slot.compare_exchange_weak(cur, key, std::memory_order_relaxed)) {
              }
            }
          }
        }
      });
}

// Fixed point: the reference position whose surface point lands on new pixel
// (x, y), starting from (sx, sy). True when found within a fraction of a pixel.
bool converge(const Reference& ref, const Pinhole& out, double x, double y, double& sx, double& sy,
              double& zt) {
  const double kx = ref.cam.fx / out.fx, ky = ref.cam.fy / out.fy;
  for (int it = 0; it < 4; ++it) {
    if (!ref.inside(sx, sy)) return false;
    const float zs = ref.depth_at(sx, sy);
    if (!(zs < Frame::kSky)) return false;
    double px, py;
    if (!out.project(ref.cam.unproject(sx, sy, zs), px, py, zt)) return false;
    const double ex = x - px, ey = y - py;
    if (ex * ex + ey * ey < 0.01) return true;
    if (it == 3) return ex * ex + ey * ey < 0.25;
    sx += ex * kx;
    sy += ey * ky;
  }
  return false;
}

// The reference sees sky where the new pixel looks (at infinity).
bool sees_sky(const Reference& ref, const Pinhole& out, double x, double y, double& sx,
              double& sy) {
  if (!ref.cam.project_dir(out.ray(x, y), sx, sy) || !ref.inside(sx, sy)) return false;
  return !(ref.depth_nearest(sx, sy) < Frame::kSky) ||
         !(ref.depth_nearest(sx + 0.5, sy + 0.5) < Frame::kSky) ||
         !(ref.depth_nearest(sx - 0.5, sy - 0.5) < Frame::kSky);
}

struct Resolver {
  const Reference& ref;
  const Reference* second;
  const Pinhole& out;
  const SplatMap& map;
  const std::vector<std::uint32_t>& win;
  bool keep_sources;
  WarpedFrame& result;

  // Where winner `key` says new pixel (x, y) reads the reference; its depth.
  bool from_winner(std::uint32_t key, double x, double y, double& sx, double& sy, float& zt) const {
    const int i = key_i(key), j = key_j(key);
    float lx, ly;
    if (!map.land(i, j, ref.frame.depth[std::size_t(j) * ref.cam.w + i], lx, ly, zt)) return false;
    sx = i + 0.5 + (x - lx) * (ref.cam.fx / out.fx);
    sy = j + 0.5 + (y - ly) * (ref.cam.fy / out.fy);
    return true;
  }

  // The farthest winner among the 5 x 5 neighbours of (px, py), or kEmpty.
  std::uint32_t farthest_neighbour(int px, int py) const {
    std::uint32_t best = kEmpty;
    float best_z = -1.f;
    for (int r = 1; r <= 2 && best == kEmpty; ++r)
      for (int b = std::max(py - r, 0); b <= std::min(py + r, out.h - 1); ++b)
        for (int a = std::max(px - r, 0); a <= std::min(px + r, out.w - 1); ++a) {
          const std::uint32_t k = win[std::size_t(b) * out.w + a];
          if (k == kEmpty) continue;
          const float z = key_depth(map, ref, k);
          if (z > best_z) {
            best_z = z;
            best = k;
          }
        }
    return best;
  }

  void write(std::size_t at, double sx, double sy, double zt) {
    ref.color_at(sx, sy, result.frame.color.rgba.data() + at * 4);
    result.frame.depth[at] = float(zt);
    result.holes[at] = 0;
    if (keep_sources) {
      result.source_x[at] = float(sx);
      result.source_y[at] = float(sy);
    }
  }

  // Pixel (px, py) with a winner whose landing point says where to read.
  bool winner(std::uint32_t key, int px, int py) {
    double sx, sy;
    float zt;
    if (!from_winner(key, px + 0.5, py + 0.5, sx, sy, zt)) return false;
    write(std::size_t(py) * out.w + px, sx, sy, zt);
    return true;
  }

  // Pixel (px, py) without a winner: iterate from the farthest neighbouring
  // winner to the real-frame point that lands on it, or sky where the real
  // frame sees sky in its direction; else a hole, read from the second
  // reference when there is one. False when neither reference sees it.
  bool search(int px, int py) {
    const std::size_t at = std::size_t(py) * out.w + px;
    const double x = px + 0.5, y = py + 0.5;
    double sx, sy, zt = Frame::kSky;
    float zf;
    const std::uint32_t key = win[at];
    bool ok = key != kEmpty && from_winner(key, x, y, sx, sy, zf);
    std::uint32_t nb = kEmpty;
    if (ok) {
      zt = zf;
    } else {
      nb = farthest_neighbour(px, py);
      ok =
          nb != kEmpty && from_winner(nb, x, y, sx, sy, zf) && converge(ref, out, x, y, sx, sy, zt);
      if (!ok && sees_sky(ref, out, x, y, sx, sy)) {
        ok = true;
        zt = Frame::kSky;
      }
    }
    if (ok) {
      write(at, sx, sy, zt);
      return true;
    }
    return hole(px, py, nb);
  }

  // A pixel neither the real frame's surfaces nor its sky cover; `nb` its
  // farthest_neighbour.
  bool hole(int px, int py, std::uint32_t nb) {
    const std::size_t at = std::size_t(py) * out.w + px;
    result.holes[at] = 1;
    result.frame.depth[at] = Frame::kSky;
    std::memset(result.frame.color.rgba.data() + at * 4, 0, 4);
    if (keep_sources) {
      result.source_x[at] = result.source_y[at] = std::numeric_limits<float>::quiet_NaN();
    }
    return second && from_second(px, py, nb, result.frame.color.rgba.data() + at * 4);
  }

  // A hole of the primary reference read from the second one: start where
  // the pixel's ray at its neighbours' (background) depth lands.
  bool from_second(int px, int py, std::uint32_t nb, std::uint8_t* rgba) {
    const std::size_t at = std::size_t(py) * out.w + px;
    const double x = px + 0.5, y = py + 0.5;
    double sx, sy, zt, d;
    if (nb != kEmpty) {
      const float z = key_depth(map, ref, nb);
      if (second->cam.project(out.unproject(x, y, z), sx, sy, d) &&
          converge(*second, out, x, y, sx, sy, zt)) {
        second->color_at(sx, sy, rgba);
        result.frame.depth[at] = float(zt);
        return true;
      }
    }
    if (sees_sky(*second, out, x, y, sx, sy)) {
      second->color_at(sx, sy, rgba);
      return true;
    }
    return false;
  }
};

// Fills the unresolved pixels of one row from the farther of their resolved
// neighbours on the row (background extension); rows with none stay sky.
void extend_background(WarpedFrame& r, int y, const std::uint8_t* miss) {
  const int w = r.frame.width();
  float* depth = r.frame.depth.data() + std::size_t(y) * w;
  for (int x = 0; x < w;) {
    if (!miss[x]) {
      ++x;
      continue;
    }
    int e = x;
    while (e < w && miss[e]) ++e;
    const int left = x - 1, right = e < w ? e : -1;
    int from = left;
    if (left < 0 || (right >= 0 && depth[right] > depth[left])) from = right;
    if (from >= 0)
      for (int k = x; k < e; ++k) {
        std::memcpy(r.frame.color.px(k, y), r.frame.color.px(from, y), 4);
        depth[k] = depth[from];
      }
    x = e;
  }
}

// One span of an output row, first mapped in a loop without branches that
// vectorises (map_span), then read pixel by pixel (resolve_span).
constexpr int kSpan = 128;
enum Kind : std::uint8_t { kWinner, kEmptyPixel, kSearch };

struct SpanMap {
  float sx[kSpan], sy[kSpan], zt[kSpan];  // where to read the reference; target depth
  int off[kSpan];                         // bilinear taps at (sx, sy)
  std::uint32_t wx[kSpan], wy[kSpan];
  std::uint8_t kind[kSpan];  // Kind
  std::uint8_t sky[kSpan];   // empty pixel: its direction lies inside the reference
};

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

// near[x] = 1 where output rows y-2..y+2, columns x-2..x+2 hold a winner
// (the neighbourhood Resolver::farthest_neighbour searches); `column` is
// scratch of w bytes.
TS_CLONES_AVX2
void near_winners(const std::uint32_t* win, int w, int h, int y, std::uint8_t* __restrict column,
                  std::uint8_t* __restrict near) {
  for (int x = 0; x < w; ++x) column[x] = 0;
  for (int b = std::max(y - 2, 0); b <= std::min(y + 2, h - 1); ++b) {
    const std::uint32_t* k = win + std::size_t(b) * w;
    for (int x = 0; x < w; ++x) column[x] |= std::uint8_t(k[x] != kEmpty);
  }
  for (int x = 2; x < w - 2; ++x)
    near[x] = column[x - 2] | column[x - 1] | column[x] | column[x + 1] | column[x + 2];
  for (int x : {0, 1, w - 2, w - 1}) {
    if (x < 0 || x >= w) continue;
    std::uint8_t any = 0;
    for (int a = std::max(x - 2, 0); a <= std::min(x + 2, w - 1); ++a) any |= column[a];
    near[x] = any;
  }
}

// Whether the reference sees sky at one of three probes around (sx, sy)
// (as sees_sky), clamped to the image; no branches.
inline int sky_probes(float sx, float sy, const float* ref_depth, int sw, int sh) {
  const float wmax = float(sw - 1), hmax = float(sh - 1);
  auto sky_at = [&](float px, float py) {
    px = px > 0.f ? px : 0.f;
    py = py > 0.f ? py : 0.f;
    px = px < wmax ? px : wmax;
    py = py < hmax ? py : hmax;
    return int(!(ref_depth[int(py) * sw + int(px)] < Frame::kSky));
  };
  return sky_at(sx, sy) | sky_at(sx + 0.5f, sy + 0.5f) | sky_at(sx - 0.5f, sy - 0.5f);
}

// An empty pixel with no winner within 2 px (`near` false) whose direction
// lies in the reference where it sees sky: sky, its colour already read from
// that direction.
inline int sky_direct(const SpanMap& m, int k, std::uint8_t near, const float* ref_depth, int sw,
                      int sh) {
  return (m.kind[k] == kEmptyPixel) & (near == 0) & (m.sky[k] != 0) &
         sky_probes(m.sx[k], m.sy[k], ref_depth, sw, sh);
}

// After map_span, pixels [0, n) of a span with many empty pixels (`near`
// and `depth` start at its first pixel): the sky_direct ones settled, depth
// of all but the rest written, visit[k] = 1 for the rest, which the
// resolver visits one at a time (searches, cracks, holes). No branches: the
// loop vectorises.
TS_CLONES_AVX2
void classify_span(const SpanMap& m, const std::uint8_t* __restrict near,
                   const float* __restrict ref_depth, int sw, int sh, int n,
                   float* __restrict depth, std::uint8_t* __restrict visit) {
  for (int k = 0; k < n; ++k) {
    const int sky = sky_direct(m, k, near[k], ref_depth, sw, sh);
    depth[k] = sky ? Frame::kSky : m.zt[k];
    visit[k] = std::uint8_t((m.kind[k] != kWinner) & (1 - sky));
  }
}

}  // namespace

void warp_depth(const Reference& ref, const Reference* second, const Pinhole& out,
                const WarpOptions& options, WarpedFrame& result, Warper::Scratch& scratch) {
  const SplatMap map(ref.cam, out);
  const SkyMap sky(ref.cam, out);
  const std::size_t n = std::size_t(out.w) * out.h;
  std::vector<std::uint32_t>& win = scratch.win;
  win.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 16),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::fill(win.begin() + r.begin(), win.begin() + r.end(), kEmpty);
                    });
  splat(ref, map, out.w, out.h, win);
  const Resolver res{ref, second, out, map, win, options.keep_sources, result};
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
