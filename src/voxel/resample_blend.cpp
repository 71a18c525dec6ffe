// SPDX-License-Identifier: MIT
#include "voxel/resample_blend.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "common/simd.h"

#if TS_HAVE_TARGET_AVX2
#include <immintrin.h>
#endif

namespace terrasprite {
namespace {

constexpr float kSky = std::numeric_limits<float>::infinity();

// Pixel j of the span. The channels are one 4-lane vector (one conversion,
// multiply and add instead of three of each); per lane the arithmetic and
// its order are the AVX2 kernel's (no FMA anywhere), so the bits are the same.
[[gnu::always_inline]] inline void blend_one(const ResampleTaps& t, int j,
                                             const PlaneSample* samples, std::uint32_t sky,
                                             std::uint8_t* row, float* depth) {
  using simd::v4f;
  using simd::v4i;
  v4f acc{};
  float wsum = 0, wbest = -1, dsum = 0, dmin = kSky, dmax = 0, dbest = kSky;
  bool all_hit = true;
  for (int a = 0; a < 2; ++a) {
    const float wc = a ? t.fc[j] : 1 - t.fc[j];
    for (int b = 0; b < 2; ++b) {
      if (!((t.ok[j] >> (2 * a + b)) & 1u)) continue;
      const float wgt = wc * (b ? t.fk[j] : 1 - t.fk[j]);
      const PlaneSample& smp = samples[t.at[a][j] + std::size_t(b)];
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
  const int x = t.x0 + j;
  std::memcpy(row + std::size_t(x) * 4, &c, 4);
  const bool smooth = wsum > 0 && all_hit && dmax - dmin <= 0.3f * dmin;
  depth[x] = smooth ? dsum / wsum : dbest;
}

#if TS_HAVE_TARGET_AVX2
// Eight size_t indices to eight int32 lanes (each below 2^31 - 1).
TS_TARGET_AVX2 inline __m256i low_dwords(const std::size_t* at) {
  const __m256i pick = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  const __m256i lo =
      _mm256_permutevar8x32_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(at)), pick);
  const __m256i hi = _mm256_permutevar8x32_epi32(
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(at + 4)), pick);
  return _mm256_permute2x128_si256(lo, hi, 0x20);
}

// A channel's weighted sum to its byte: acc / wsum + 0.5, at most 255, truncated.
TS_TARGET_AVX2 inline __m256i quantise(__m256 acc, __m256 inv) {
  const __m256 top = _mm256_set1_ps(255.f);
  __m256 v = _mm256_add_ps(_mm256_mul_ps(acc, inv), _mm256_set1_ps(0.5f));
  v = _mm256_blendv_ps(v, top, _mm256_cmp_ps(v, top, _CMP_GT_OQ));
  return _mm256_and_si256(_mm256_cvttps_epi32(v), _mm256_set1_epi32(0xff));
}

// Pixels j .. j + 7: blend_one per lane, a sample's absence a lane mask (its
// weight zeroed, which adds +0 to the sums as the skip did; the gathers read
// nothing there).
TS_TARGET_AVX2 void blend_eight(const ResampleTaps& t, int j, const PlaneSample* samples,
                                std::uint32_t sky, std::uint8_t* row, float* depth) {
  const __m256 one = _mm256_set1_ps(1.f), zero = _mm256_setzero_ps();
  const __m256 inf = _mm256_set1_ps(kSky);
  const __m256i byte = _mm256_set1_epi32(0xff);
  const __m256 fc = _mm256_loadu_ps(t.fc + j), fk = _mm256_loadu_ps(t.fk + j);
  const __m256i ok = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(t.ok + j));
  const auto* colors = reinterpret_cast<const int*>(samples);
  const float* depths = reinterpret_cast<const float*>(samples) + 1;
  __m256 ar = zero, ag = zero, ab = zero, wsum = zero, dsum = zero;
  __m256 wbest = _mm256_set1_ps(-1.f), dbest = inf, dmin = inf, dmax = zero;
  __m256 all_hit = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
  for (int a = 0; a < 2; ++a) {
    const __m256i idx = low_dwords(t.at[a] + j);
    const __m256 wc = a ? fc : _mm256_sub_ps(one, fc);
    for (int b = 0; b < 2; ++b) {
      const __m256i bit = _mm256_set1_epi32(1 << (2 * a + b));
      const __m256i mi = _mm256_cmpeq_epi32(_mm256_and_si256(ok, bit), bit);
      const __m256 m = _mm256_castsi256_ps(mi);
      const __m256 wgt = _mm256_mul_ps(wc, b ? fk : _mm256_sub_ps(one, fk));
      const __m256i vi = b ? _mm256_add_epi32(idx, _mm256_set1_epi32(1)) : idx;
      const __m256i col = _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), colors, vi, mi, 8);
      const __m256 d = _mm256_mask_i32gather_ps(zero, depths, vi, m, 8);
      const __m256 wm = _mm256_and_ps(wgt, m);
      const __m256 r = _mm256_cvtepi32_ps(_mm256_and_si256(col, byte));
      const __m256 g = _mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srli_epi32(col, 8), byte));
      const __m256 bl = _mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srli_epi32(col, 16), byte));
      ar = _mm256_add_ps(ar, _mm256_mul_ps(wm, r));
      ag = _mm256_add_ps(ag, _mm256_mul_ps(wm, g));
      ab = _mm256_add_ps(ab, _mm256_mul_ps(wm, bl));
      wsum = _mm256_add_ps(wsum, wm);
      dsum = _mm256_blendv_ps(dsum, _mm256_add_ps(dsum, _mm256_mul_ps(wgt, d)), m);
      all_hit = _mm256_andnot_ps(_mm256_and_ps(m, _mm256_cmp_ps(d, inf, _CMP_NLT_UQ)), all_hit);
      dmin = _mm256_blendv_ps(dmin, _mm256_min_ps(d, dmin), m);  // d < dmin ? d : dmin
      dmax = _mm256_blendv_ps(dmax, _mm256_max_ps(d, dmax), m);  // d > dmax ? d : dmax
      const __m256 upd = _mm256_and_ps(m, _mm256_cmp_ps(wgt, wbest, _CMP_GT_OQ));
      wbest = _mm256_blendv_ps(wbest, wgt, upd);
      dbest = _mm256_blendv_ps(dbest, d, upd);
    }
  }
  const __m256 has = _mm256_cmp_ps(wsum, zero, _CMP_GT_OQ);
  const __m256 inv = _mm256_div_ps(one, wsum);
  __m256i c = _mm256_or_si256(_mm256_set1_epi32(int(0xff000000u)), quantise(ar, inv));
  c = _mm256_or_si256(c, _mm256_slli_epi32(quantise(ag, inv), 8));
  c = _mm256_or_si256(c, _mm256_slli_epi32(quantise(ab, inv), 16));
  c = _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(_mm256_set1_epi32(int(sky))),
                                           _mm256_castsi256_ps(c), has));
  const int x = t.x0 + j;
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(row + std::size_t(x) * 4), c);
  const __m256 spread = _mm256_cmp_ps(_mm256_sub_ps(dmax, dmin),
                                      _mm256_mul_ps(_mm256_set1_ps(0.3f), dmin), _CMP_LE_OQ);
  const __m256 smooth = _mm256_and_ps(_mm256_and_ps(has, all_hit), spread);
  _mm256_storeu_ps(depth + x, _mm256_blendv_ps(dbest, _mm256_div_ps(dsum, wsum), smooth));
}

TS_TARGET_AVX2 void blend_span_avx2(const ResampleTaps& t, const PlaneSample* samples,
                                    std::uint32_t sky, std::uint8_t* row, float* depth) {
  int j = 0;
  for (; j + 8 <= t.count; j += 8) blend_eight(t, j, samples, sky, row, depth);
  for (; j < t.count; ++j) blend_one(t, j, samples, sky, row, depth);
}
#endif

}  // namespace

TS_CLONES_AVX2
void blend_taps_scalar(const ResampleTaps& taps, const PlaneSample* samples, std::uint32_t sky,
                       std::uint8_t* row, float* depth) {
  for (int j = 0; j < taps.count; ++j) blend_one(taps, j, samples, sky, row, depth);
}

bool blend_taps_avx2(const ResampleTaps& taps, const PlaneSample* samples, std::uint32_t sky,
                     std::uint8_t* row, float* depth) {
#if TS_HAVE_TARGET_AVX2
  blend_span_avx2(taps, samples, sky, row, depth);
  return true;
#else
  (void)taps, (void)samples, (void)sky, (void)row, (void)depth;
  return false;
#endif
}

void blend_taps(const ResampleTaps& taps, const PlaneSample* samples, std::size_t sample_count,
                std::uint32_t sky, std::uint8_t* row, float* depth) {
  constexpr std::size_t kGatherLimit = (std::size_t(1) << 31) - 1;  // int32 indices, + 1
  if (simd::has_avx2() && sample_count < kGatherLimit &&
      blend_taps_avx2(taps, samples, sky, row, depth))
    return;
  blend_taps_scalar(taps, samples, sky, row, depth);
}

}  // namespace terrasprite
