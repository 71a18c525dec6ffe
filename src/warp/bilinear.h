// SPDX-License-Identifier: MIT
// The warps' bilinear read of an RGBA8 reference, split in two so loops
// vectorise: tap() turns a position into a 2 x 2 block and 8-bit weights
// (pure arithmetic, no branches); bilinear_block() reads and blends one
// block, bilinear_span() a span of them across vector lanes (the same bits).
#pragma once
#include <cstdint>

#include "common/packed_rgba.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace terrasprite::warp {

/// Position (x, y) in pixels (centres at +0.5) of a w x h image (w, h >= 2),
/// clamped to it: the block's top-left texel index and weights in 0..256
/// (0: exactly that texel). NaN reads the top-left corner.
inline void tap(float x, float y, int w, int h, int& offset, std::uint32_t& fi, std::uint32_t& fj) {
  const float wmax = float(w - 1), hmax = float(h - 1);
  float px = x - 0.5f, py = y - 0.5f;
  px = px > 0.f ? px : 0.f;
  py = py > 0.f ? py : 0.f;
  px = px < wmax ? px : wmax;
  py = py < hmax ? py : hmax;
  int i0 = int(px), j0 = int(py);
  i0 = i0 < w - 2 ? i0 : w - 2;
  j0 = j0 < h - 2 ? j0 : h - 2;
  fi = std::uint32_t(int((px - float(i0)) * 256.f + 0.5f));
  fj = std::uint32_t(int((py - float(j0)) * 256.f + 0.5f));
  offset = j0 * w + i0;
}

/// Bilinear RGBA8 of the 2 x 2 block whose top-left texel is src[o] (row
/// stride w), weights from tap().
inline std::uint32_t bilinear_block(const std::uint32_t* src, int o, int w, std::uint32_t fi,
                                    std::uint32_t fj) {
#if defined(__SSE2__)
  // Both columns at once in 16-bit lanes: vertical lerp, then the two halves.
  const __m128i z = _mm_setzero_si128(), half = _mm_set1_epi16(128);
  const __m128i ab =
      _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(src + o)), z);
  const __m128i cd =
      _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(src + o + w)), z);
  const __m128i v = _mm_srli_epi16(
      _mm_add_epi16(_mm_add_epi16(_mm_mullo_epi16(ab, _mm_set1_epi16(short(256 - fj))),
                                  _mm_mullo_epi16(cd, _mm_set1_epi16(short(fj)))),
                    half),
      8);
  const __m128i wi = _mm_unpacklo_epi64(_mm_set1_epi16(short(256 - fi)), _mm_set1_epi16(short(fi)));
  __m128i h = _mm_mullo_epi16(v, wi);
  h = _mm_srli_epi16(_mm_add_epi16(_mm_add_epi16(h, _mm_srli_si128(h, 8)), half), 8);
  return std::uint32_t(_mm_cvtsi128_si32(_mm_packus_epi16(h, h)));
#else
  return lerp_packed(lerp_packed(src[o], src[o + 1], fi),
                     lerp_packed(src[o + w], src[o + w + 1], fi), fj);
#endif
}

/// out[k] = bilinear_block(src, off[k], w, wx[k], wy[k]) for k < n, blended
/// across vector lanes (packed 16-bit channel pairs in 32-bit lanes). The
/// same bits as bilinear_block: vertical lerp first, each rounded.
void bilinear_span(const std::uint32_t* src, int w, const int* off, const std::uint32_t* wx,
                   const std::uint32_t* wy, int n, std::uint32_t* out);

}  // namespace terrasprite::warp
