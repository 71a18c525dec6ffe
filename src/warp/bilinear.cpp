// SPDX-License-Identifier: MIT
// bilinear_span(): the warps' bilinear reads of a whole span. With AVX2,
// four pixels at a time: each pixel's 2 x 2 block is two 8-byte loads, its
// channels widened to 16-bit lanes, two pixels per 256-bit register; the
// arithmetic is bilinear_block's, so the bits are too.
#include "warp/bilinear.h"

#include "common/simd.h"

#if TS_HAVE_TARGET_AVX2
#include <immintrin.h>

#include <cstring>
#endif

namespace terrasprite::warp {
namespace {

#if TS_HAVE_TARGET_AVX2
TS_TARGET_AVX2 inline __m128i load_pair(const std::uint32_t* p0, const std::uint32_t* p1) {
  std::int64_t a, b;
  std::memcpy(&a, p0, 8);
  std::memcpy(&b, p1, 8);
  return _mm_set_epi64x(b, a);
}

// Two pixels' blocks (one per 128-bit lane, 16-bit lanes: top row's left
// and right texels, likewise `bottom`) and their weights (`pick` selects
// each lane's pixel from fx, fy): bilinear_block's arithmetic, the result in
// each lane's low four 16-bit lanes.
TS_TARGET_AVX2 inline __m256i blend(__m256i top, __m256i bottom, __m256i fx, __m256i fy,
                                    __m256i pick) {
  const __m256i half = _mm256_set1_epi16(128), full = _mm256_set1_epi16(256);
  const __m256i fj = _mm256_shuffle_epi8(fy, pick);
  const __m256i v = _mm256_srli_epi16(
      _mm256_add_epi16(_mm256_add_epi16(_mm256_mullo_epi16(top, _mm256_sub_epi16(full, fj)),
                                        _mm256_mullo_epi16(bottom, fj)),
                       half),
      8);
  const __m256i fi = _mm256_shuffle_epi8(fx, pick);
  const __m256i wi = _mm256_blend_epi16(_mm256_sub_epi16(full, fi), fi, 0xF0);
  const __m256i h = _mm256_mullo_epi16(v, wi);
  return _mm256_srli_epi16(_mm256_add_epi16(_mm256_add_epi16(h, _mm256_srli_si256(h, 8)), half), 8);
}

// Pixels k..k+3: registers hold pixels (0, 2) in "lo" and (1, 3) in "hi", one
// per 128-bit lane; each pixel's 16-bit lanes are its left texel's RGBA then
// its right texel's.
TS_TARGET_AVX2
void bilinear_span_avx2(const std::uint32_t* src, int w, const int* off, const std::uint32_t* wx,
                        const std::uint32_t* wy, int n, std::uint32_t* out) {
  const __m256i z = _mm256_setzero_si256();
  // Broadcast a pixel's 16-bit weight over its 128-bit lane: pixel 0 / 2
  // (dwords 0 and 2), pixel 1 / 3 (dwords 1 and 3).
  const __m256i pick_lo = _mm256_setr_epi8(0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 8, 9, 8,
                                           9, 8, 9, 8, 9, 8, 9, 8, 9, 8, 9, 8, 9);
  const __m256i pick_hi = _mm256_setr_epi8(4, 5, 4, 5, 4, 5, 4, 5, 4, 5, 4, 5, 4, 5, 4, 5, 12, 13,
                                           12, 13, 12, 13, 12, 13, 12, 13, 12, 13, 12, 13, 12, 13);
  const __m256i order = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  int k = 0;
  for (; k + 4 <= n; k += 4) {
    const std::uint32_t* p0 = src + off[k];
    const std::uint32_t* p1 = src + off[k + 1];
    const std::uint32_t* p2 = src + off[k + 2];
    const std::uint32_t* p3 = src + off[k + 3];
    // Bytes: lane 0 = pixels 0, 1; lane 1 = pixels 2, 3.
    const __m256i ab = _mm256_set_m128i(load_pair(p2, p3), load_pair(p0, p1));
    const __m256i cd = _mm256_set_m128i(load_pair(p2 + w, p3 + w), load_pair(p0 + w, p1 + w));
    const __m256i ab_lo = _mm256_unpacklo_epi8(ab, z), ab_hi = _mm256_unpackhi_epi8(ab, z);
    const __m256i cd_lo = _mm256_unpacklo_epi8(cd, z), cd_hi = _mm256_unpackhi_epi8(cd, z);
    const __m256i fy =
        _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(wy + k)));
    const __m256i fx =
        _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(wx + k)));
    const __m256i lo = blend(ab_lo, cd_lo, fx, fy, pick_lo),
                  hi = blend(ab_hi, cd_hi, fx, fy, pick_hi);
    // Dwords: lane 0 = (p0, -, p1, -), lane 1 = (p2, -, p3, -).
    const __m256i packed = _mm256_permutevar8x32_epi32(_mm256_packus_epi16(lo, hi), order);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + k), _mm256_castsi256_si128(packed));
  }
  for (; k < n; ++k) out[k] = bilinear_block(src, off[k], w, wx[k], wy[k]);
}
#endif

}  // namespace

void bilinear_span(const std::uint32_t* src, int w, const int* off, const std::uint32_t* wx,
                   const std::uint32_t* wy, int n, std::uint32_t* out) {
#if TS_HAVE_TARGET_AVX2
  if (simd::has_avx2()) return bilinear_span_avx2(src, w, off, wx, wy, n, out);
#endif
  for (int k = 0; k < n; ++k) out[k] = bilinear_block(src, off[k], w, wx[k], wy[k]);
}

}  // namespace terrasprite::warp
