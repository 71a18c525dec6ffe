// SPDX-License-Identifier: MIT
// Input checks and plane extraction shared by the metrics.
#include "quality/planes.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "common/simd.h"
#include "terrasprite/common/error.h"

// Built for AVX2 and the baseline (as filter.cpp): the 8-bit -> float luma
// loop only vectorises well with AVX2's wider shuffles.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TS_INLINE __attribute__((always_inline)) inline
#else
#define TS_INLINE inline
#endif

namespace terrasprite::quality::detail {

namespace {

void check_view(const char* metric, const char* which, const ImageView& v) {
  if (v.width <= 0 || v.height <= 0)
    throw InputError(
        fmt::format("{}: {} image is empty ({}x{})", metric, which, v.width, v.height));
  if (v.channels != 1 && v.channels != 3 && v.channels != 4)
    throw InputError(fmt::format("{}: {} image has {} channels (1, 3 or 4 supported)", metric,
                                 which, v.channels));
  const auto row_bytes = static_cast<std::size_t>(v.width) * v.channels;
  if (static_cast<std::size_t>(v.stride) < row_bytes ||
      v.data.size() < static_cast<std::size_t>(v.stride) * (v.height - 1) + row_bytes)
    throw InputError(fmt::format("{}: {} image view ({}x{}, stride {}) is larger than its {} bytes",
                                 metric, which, v.width, v.height, v.stride, v.data.size()));
}

}  // namespace

void check_inputs(const char* metric, const ImageView& reference, const ImageView& test,
                  Mask mask) {
  check_view(metric, "reference", reference);
  check_view(metric, "test", test);
  if (reference.width != test.width || reference.height != test.height)
    throw InputError(fmt::format("{}: images differ in size: reference {}x{}, test {}x{}", metric,
                                 reference.width, reference.height, test.width, test.height));
  const auto n = static_cast<std::size_t>(reference.width) * reference.height;
  if (!mask.empty() && mask.size() != n)
    throw InputError(fmt::format("{}: mask has {} bytes, the {}x{} images need {}", metric,
                                 mask.size(), reference.width, reference.height, n));
}

namespace {

// One row of a plane, with the channel count and the channel fixed at compile
// time so the loop is a plain vectorisable gather-and-scale.
template <int C>
TS_INLINE void extract_row(const std::uint8_t* __restrict src, int width, Channel channel,
                           float* __restrict dst) {
  const int k = C == 1 ? 0 : (channel == Channel::kG ? 1 : channel == Channel::kB ? 2 : 0);
  if (channel == Channel::kLuma && C != 1) {
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* p = src + static_cast<std::size_t>(x) * C;
      dst[x] = luma(p[0], p[1], p[2]);
    }
  } else if (channel == Channel::kLuma) {
    for (int x = 0; x < width; ++x) dst[x] = luma(src[x], src[x], src[x]);
  } else {
    for (int x = 0; x < width; ++x)
      dst[x] = static_cast<float>(src[static_cast<std::size_t>(x) * C + k]);
  }
}

}  // namespace

TS_CLONES_AVX2 void extract_row(const ImageView& image, Channel channel, int y, float* dst) {
  switch (image.channels) {
    case 1:
      extract_row<1>(image.row(y), image.width, channel, dst);
      break;
    case 3:
      extract_row<3>(image.row(y), image.width, channel, dst);
      break;
    default:
      extract_row<4>(image.row(y), image.width, channel, dst);
      break;
  }
}

Plane extract(const ImageView& image, Channel channel) {
  Plane p(image.width, image.height);
  tbb::parallel_for(0, image.height, [&](int y) { extract_row(image, channel, y, p.row(y)); });
  return p;
}

std::size_t mask_count(Mask mask, int width, int height) {
  if (mask.empty()) return static_cast<std::size_t>(width) * height;
  std::size_t n = 0;
  for (auto m : mask) n += m != 0;
  return n;
}

}  // namespace terrasprite::quality::detail
