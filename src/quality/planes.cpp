// SPDX-License-Identifier: MIT
// Input checks and plane extraction shared by the metrics.
#include "quality/planes.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "terrasprite/error.h"

namespace terrasprite::quality::detail {

namespace {

void check_view(const char* metric, const char* which, const ImageView& v) {
  if (v.width <= 0 || v.height <= 0)
    throw InputError(fmt::format("{}: {} image is empty ({}x{})", metric, which, v.width, v.height));
  if (v.channels != 1 && v.channels != 3 && v.channels != 4)
    throw InputError(fmt::format("{}: {} image has {} channels (1, 3 or 4 supported)", metric, which, v.channels));
  const auto row_bytes = static_cast<std::size_t>(v.width) * v.channels;
  if (static_cast<std::size_t>(v.stride) < row_bytes ||
      v.data.size() < static_cast<std::size_t>(v.stride) * (v.height - 1) + row_bytes)
    throw InputError(fmt::format("{}: {} image view ({}x{}, stride {}) is larger than its {} bytes", metric, which,
                                 v.width, v.height, v.stride, v.data.size()));
}

}  // namespace

void check_inputs(const char* metric, const ImageView& reference, const ImageView& test, Mask mask) {
  check_view(metric, "reference", reference);
  check_view(metric, "test", test);
  if (reference.width != test.width || reference.height != test.height)
    throw InputError(fmt::format("{}: images differ in size: reference {}x{}, test {}x{}", metric, reference.width,
                                 reference.height, test.width, test.height));
  const auto n = static_cast<std::size_t>(reference.width) * reference.height;
  if (!mask.empty() && mask.size() != n)
    throw InputError(fmt::format("{}: mask has {} bytes, the {}x{} images need {}", metric, mask.size(),
                                 reference.width, reference.height, n));
}

Plane extract(const ImageView& image, Channel channel) {
  Plane p(image.width, image.height);
  tbb::parallel_for(0, image.height, [&](int y) {
    const std::uint8_t* src = image.row(y);
    float* dst = p.row(y);
    for (int x = 0; x < image.width; ++x) {
      int r, g, b;
      rgb_at(src, image.channels, x, r, g, b);
      switch (channel) {
        case Channel::kLuma: dst[x] = luma(r, g, b); break;
        case Channel::kR: dst[x] = static_cast<float>(r); break;
        case Channel::kG: dst[x] = static_cast<float>(g); break;
        case Channel::kB: dst[x] = static_cast<float>(b); break;
      }
    }
  });
  return p;
}

std::size_t mask_count(Mask mask, int width, int height) {
  if (mask.empty()) return static_cast<std::size_t>(width) * height;
  std::size_t n = 0;
  for (auto m : mask) n += m != 0;
  return n;
}

}  // namespace terrasprite::quality::detail
