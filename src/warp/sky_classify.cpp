// SPDX-License-Identifier: MIT
// Sky classification of the depth warp's empty pixels (see sky_classify.h):
// loops without branches that vectorise, in an AVX2 clone and a baseline one.
#include "warp/sky_classify.h"

#include <algorithm>

#include "common/simd.h"

namespace terrasprite::warp {

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

}  // namespace terrasprite::warp
