// SPDX-License-Identifier: MIT
// The depth warp's pixels visited one at a time (see crack_search.h): the
// fixed-point crack search, sky in the pixel's direction, holes from the
// second reference, background extension.
#include "warp/crack_search.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace terrasprite::warp {
namespace {

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

}  // namespace

// Where winner `key` says new pixel (x, y) reads the reference; its depth.
bool Resolver::from_winner(std::uint32_t key, double x, double y, double& sx, double& sy,
                           float& zt) const {
  const int i = key_i(key), j = key_j(key);
  float lx, ly;
  if (!map.land(i, j, ref.frame.depth[std::size_t(j) * ref.cam.w + i], lx, ly, zt)) return false;
  sx = i + 0.5 + (x - lx) * (ref.cam.fx / out.fx);
  sy = j + 0.5 + (y - ly) * (ref.cam.fy / out.fy);
  return true;
}

// The farthest winner among the 5 x 5 neighbours of (px, py), or kEmpty.
std::uint32_t Resolver::farthest_neighbour(int px, int py) const {
  std::uint32_t best = kEmpty;
  float best_z = -1.f;
  for (int r = 1; r <= 2 && best == kEmpty; ++r)
    for (int b = std::max(py - r, 0); b <= std::min(py + r, out.h - 1); ++b)
      for (int a = std::max(px - r, 0); a <= std::min(px + r, out.w - 1); ++a) {
        const std::uint32_t k = win[std::size_t(b) * out.w + a];
        if (k == kEmpty) continue;
        const float z = win_depth[std::size_t(b) * out.w + a];
        if (z > best_z) {
          best_z = z;
          best = k;
        }
      }
  return best;
}

void Resolver::write(std::size_t at, double sx, double sy, double zt) {
  ref.color_at(sx, sy, result.frame.color.rgba.data() + at * 4);
  result.frame.depth[at] = float(zt);
  result.holes[at] = 0;
  if (keep_sources) {
    result.source_x[at] = float(sx);
    result.source_y[at] = float(sy);
  }
}

// Pixel (px, py) with a winner whose landing point says where to read.
bool Resolver::winner(std::uint32_t key, int px, int py) {
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
bool Resolver::search(int px, int py) {
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
    ok = nb != kEmpty && from_winner(nb, x, y, sx, sy, zf) && converge(ref, out, x, y, sx, sy, zt);
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
bool Resolver::hole(int px, int py, std::uint32_t nb) {
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
bool Resolver::from_second(int px, int py, std::uint32_t nb, std::uint8_t* rgba) {
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

}  // namespace terrasprite::warp
