// SPDX-License-Identifier: MIT
// The one home of SIMD machinery: function multi-versioning, so default builds stay
// portable (no -march=native) while AVX2 machines run vector clones chosen at
// load time. TS_CLONES_AVX2: AVX2 + baseline; TS_CLONES_V3: x86-64-v3 (AVX2 +
// FMA) + baseline, for loops that gain from fused multiply-adds.
#pragma once
#include <cstdint>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TS_CLONES_AVX2 __attribute__((target_clones("avx2", "default")))
#define TS_CLONES_V3 __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define TS_CLONES_AVX2
#define TS_CLONES_V3
#endif

// For the few kernels written with AVX2 intrinsics (shuffles that vector
// extensions do not express well): TS_TARGET_AVX2 compiles one function for
// AVX2, and the caller picks it only where simd::has_avx2().
#if defined(__x86_64__) && defined(__GNUC__)
#define TS_HAVE_TARGET_AVX2 1
#define TS_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define TS_HAVE_TARGET_AVX2 0
#define TS_TARGET_AVX2
#endif

namespace terrasprite::simd {
// GCC/Clang vector extensions: element-wise arithmetic that compiles to SSE
// or AVX2 in the matching clone.
typedef double v4d __attribute__((vector_size(32)));
typedef float v4f __attribute__((vector_size(16)));
typedef float v8f __attribute__((vector_size(32)));
typedef std::int32_t v4i __attribute__((vector_size(16)));

/// The CPU runs AVX2 (checked once); false where TS_TARGET_AVX2 is empty.
inline bool has_avx2() {
#if TS_HAVE_TARGET_AVX2
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
#else
  return false;
#endif
}
}  // namespace terrasprite::simd
