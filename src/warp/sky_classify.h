// SPDX-License-Identifier: MIT
// The depth warp's empty output pixels settled across vector lanes: where
// the reference sees sky in the pixel's direction (a homography of the
// rotation alone, at infinity) and no winner lies within 2 px, the pixel is
// sky; the rest (cracks, silhouettes, holes) go to the crack search.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "terrasprite/camera/frame.h"
#include "warp/pinhole.h"
#include "warp/splat.h"

namespace terrasprite::warp {

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

// One span of an output row, first mapped in a loop without branches that
// vectorises (map_span), then read across vector lanes or one pixel at a
// time (warp_depth).
constexpr int kSpan = 128;
enum Kind : std::uint8_t { kWinner, kEmptyPixel, kSearch };

struct SpanMap {
  float sx[kSpan], sy[kSpan], zt[kSpan];  // where to read the reference; target depth
  int off[kSpan];                         // bilinear taps at (sx, sy)
  std::uint32_t wx[kSpan], wy[kSpan];
  std::uint8_t kind[kSpan];  // Kind
  std::uint8_t sky[kSpan];   // empty pixel: its direction lies inside the reference
};

// near[x] = 1 where output rows y-2..y+2, columns x-2..x+2 hold a winner
// (the neighbourhood Resolver::farthest_neighbour searches); `column` is
// scratch of w bytes.
void near_winners(const std::uint32_t* win, int w, int h, int y, std::uint8_t* __restrict column,
                  std::uint8_t* __restrict near);

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
void classify_span(const SpanMap& m, const std::uint8_t* __restrict near,
                   const float* __restrict ref_depth, int sw, int sh, int n,
                   float* __restrict depth, std::uint8_t* __restrict visit);

}  // namespace terrasprite::warp
