// SPDX-License-Identifier: MIT
#include "voxel/resample_blend.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "common/simd.h"

namespace terrasprite {
// The channels of a tap are one 4-lane vector (one conversion, multiply and
// add instead of three of each); per lane the arithmetic and its order are the
// scalar blend's (no FMA in either clone), so the bits are the same.
TS_CLONES_AVX2
void blend_taps(const ResampleTap* taps, int count, const PlaneSample* samples, std::uint32_t sky,
                std::uint8_t* row, float* depth) {
  using simd::v4f;
  using simd::v4i;
  constexpr float kSky = std::numeric_limits<float>::infinity();
  for (int j = 0; j < count; ++j) {
    const ResampleTap& t = taps[j];
    v4f acc{};
    float wsum = 0, wbest = -1, dsum = 0, dmin = kSky, dmax = 0, dbest = kSky;
    bool all_hit = true;
    for (int a = 0; a < 2; ++a) {
      const float wc = a ? t.fc : 1 - t.fc;
      for (int b = 0; b < 2; ++b) {
        if (!((t.ok >> (2 * a + b)) & 1u)) continue;
        const float wgt = wc * (b ? t.fk : 1 - t.fk);
        const PlaneSample& smp = samples[t.at[a] + std::size_t(b)];
        // Channel ch in lane ch (one broadcast, shift and mask: a byte vector's
        // conversion came out as four scalar conversions).
        const v4i p = (v4i{} + std::int32_t(smp.color)) >> v4i{0, 8, 16, 24} & 0xff;
        acc += wgt * __builtin_convertvector(p, v4f);
        wsum += wgt;
        dsum += wgt * smp.depth;
        all_hit = all_hit && smp.depth < kSky;
        dmin = std::min(dmin, smp.depth);
        dmax = std::max(dmax, smp.depth);
        if (wgt > wbest) {
          wbest = wgt;
          dbest = smp.depth;
        }
      }
    }
    std::uint32_t c = sky;
    if (wsum > 0) {
      const float inv = 1.0f / wsum;
      v4f v = acc * inv + 0.5f;
      v = v > 255.f ? v4f{} + 255.f : v;  // std::min(v, 255)
      const v4i q = __builtin_convertvector(v, v4i);
      c = 0xff000000u | std::uint32_t(q[0] & 0xff) | std::uint32_t(q[1] & 0xff) << 8 |
          std::uint32_t(q[2] & 0xff) << 16;
    }
    std::memcpy(row + std::size_t(t.x) * 4, &c, 4);
    const bool smooth = wsum > 0 && all_hit && dmax - dmin <= 0.3f * dmin;
    depth[t.x] = smooth ? dsum / wsum : dbest;
  }
}

}  // namespace terrasprite
