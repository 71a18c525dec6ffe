// SPDX-License-Identifier: MIT
#include "voxel/hit_colors.h"

#include <cstring>

#include "common/simd.h"

#if TS_HAVE_TARGET_AVX2
#include <immintrin.h>
#endif

namespace terrasprite {
namespace {

#if TS_HAVE_TARGET_AVX2
// lerp_packed (common/packed_rgba.h) on eight lanes: same integer steps.
TS_TARGET_AVX2 inline __m256i lerp8(__m256i a, __m256i b, __m256i f) {
  const __m256i m = _mm256_set1_epi32(0xff00ff), r = _mm256_set1_epi32(0x800080);
  const __m256i g = _mm256_sub_epi32(_mm256_set1_epi32(256), f);
  const __m256i rb = _mm256_and_si256(
      _mm256_srli_epi32(
          _mm256_add_epi32(_mm256_add_epi32(_mm256_mullo_epi32(_mm256_and_si256(a, m), g),
                                            _mm256_mullo_epi32(_mm256_and_si256(b, m), f)),
                           r),
          8),
      m);
  const __m256i ga = _mm256_and_si256(
      _mm256_srli_epi32(
          _mm256_add_epi32(
              _mm256_add_epi32(_mm256_mullo_epi32(_mm256_and_si256(_mm256_srli_epi32(a, 8), m), g),
                               _mm256_mullo_epi32(_mm256_and_si256(_mm256_srli_epi32(b, 8), m), f)),
              r),
          8),
      m);
  return _mm256_or_si256(rb, _mm256_slli_epi32(ga, 8));
}

// One coordinate of four hits: clamped into [0, n - 1], its cell's first
// sample (at most n - 2) and 8-bit weight, as BasicTileReader::bilinear_color.
TS_TARGET_AVX2 inline void axis4(__m256d x, int n, __m128i& x0, __m128i& fx) {
  x = _mm256_min_pd(_mm256_set1_pd(double(n - 1)), _mm256_max_pd(_mm256_setzero_pd(), x));
  x0 = _mm_min_epi32(_mm256_cvttpd_epi32(x), _mm_set1_epi32(n - 2));
  const __m256d w =
      _mm256_add_pd(_mm256_mul_pd(_mm256_sub_pd(x, _mm256_cvtepi32_pd(x0)), _mm256_set1_pd(256.0)),
                    _mm256_set1_pd(0.5));
  fx = _mm256_cvttpd_epi32(w);  // 0 .. 256: the unsigned conversion's value
}

TS_TARGET_AVX2 std::size_t hit_colors_avx2(const LevelColors& lv, const HitLine& ln,
                                           const double* t, MarchHit* hits, std::size_t count) {
  const __m256d u0 = _mm256_set1_pd(ln.u0), v0 = _mm256_set1_pd(ln.v0);
  const __m256d du = _mm256_set1_pd(ln.du), dv = _mm256_set1_pd(ln.dv);
  const __m256d sc = _mm256_set1_pd(ln.scale);
  const __m128i stride = _mm_set1_epi32(int(lv.stride));
  const __m256i pick = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  const std::uint32_t* base = lv.color + lv.off;
  std::size_t k = 0;
  for (; k + 4 <= count; k += 4) {
    const __m256d tk = _mm256_loadu_pd(t + k);
    // (u0 + t du) scale, the scalar order (no FMA in this clone).
    const __m256d i = _mm256_mul_pd(_mm256_add_pd(u0, _mm256_mul_pd(tk, du)), sc);
    const __m256d j = _mm256_mul_pd(_mm256_add_pd(v0, _mm256_mul_pd(tk, dv)), sc);
    __m128i i0, fi, j0, fj;
    axis4(i, lv.width, i0, fi);
    axis4(j, lv.height, j0, fj);
    alignas(16) std::int32_t at[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(at), _mm_add_epi32(_mm_mullo_epi32(j0, stride), i0));
    // Samples (i0, j0), (i0 + 1, j0) of each hit, then the row below.
    std::uint64_t p[8];
    for (int l = 0; l < 4; ++l) {
      std::memcpy(&p[l], base + at[l], 8);
      std::memcpy(&p[4 + l], base + at[l] + lv.stride, 8);
    }
    // Lanes 0-3: row j0, left and right samples split; lanes 4-7: row j0 + 1.
    const __m256i r0 = _mm256_permutevar8x32_epi32(_mm256_loadu_si256((const __m256i*)p), pick);
    const __m256i r1 =
        _mm256_permutevar8x32_epi32(_mm256_loadu_si256((const __m256i*)(p + 4)), pick);
    const __m256i left = _mm256_permute2x128_si256(r0, r1, 0x20);
    const __m256i right = _mm256_permute2x128_si256(r0, r1, 0x31);
    const __m256i rows = lerp8(left, right, _mm256_set_m128i(fi, fi));
    // Across the rows: lanes 0-3 against 4-7 with weight fj.
    const __m256i below = _mm256_permute2x128_si256(rows, rows, 0x11);
    const __m256i c = lerp8(rows, below, _mm256_set_m128i(fj, fj));
    alignas(16) std::uint32_t out[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(out), _mm256_castsi256_si128(c));
    for (int l = 0; l < 4; ++l) hits[k + l].color = out[l];
  }
  return k;
}
#endif

}  // namespace

std::size_t hit_colors(const LevelColors& level, const HitLine& line, const double* t,
                       MarchHit* hits, std::size_t count) {
#if TS_HAVE_TARGET_AVX2
  // 32-bit sample indices: the last row's end must fit.
  const double last = double(level.off) + double(level.height) * double(level.stride);
  if (simd::has_avx2() && level.off >= 0 && last < 2147483647.0 && level.stride < 2147483647)
    return hit_colors_avx2(level, line, t, hits, count);
#endif
  (void)level, (void)line, (void)t, (void)hits, (void)count;
  return 0;
}

}  // namespace terrasprite
