// SPDX-License-Identifier: MIT
// Difference images for looking at errors: scaled absolute difference, and a
// FLIP map through the magma colour map (as the FLIP paper shows its maps).
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "quality/magma.h"
#include "quality/planes.h"
#include "terrasprite/common/error.h"

namespace terrasprite::quality {

Image difference_image(const ImageView& reference, const ImageView& test, double scale) {
  detail::check_inputs("difference", reference, test);
  if (!std::isfinite(scale) || scale <= 0)
    throw InputError(fmt::format("difference: scale must be finite and positive, got {}", scale));
  Image out(reference.width, reference.height);
  tbb::parallel_for(0, reference.height, [&](int y) {
    for (int x = 0; x < reference.width; ++x) {
      int a[3], b[3];
      detail::rgb_at(reference.row(y), reference.channels, x, a[0], a[1], a[2]);
      detail::rgb_at(test.row(y), test.channels, x, b[0], b[1], b[2]);
      std::uint8_t* p = out.px(x, y);
      for (int c = 0; c < 3; ++c)
        p[c] =
            static_cast<std::uint8_t>(std::min(255.0, std::round(std::abs(a[c] - b[c]) * scale)));
      p[3] = 255;
    }
  });
  return out;
}

Image flip_image(std::span<const float> map, int width, int height) {
  if (width <= 0 || height <= 0)
    throw InputError(fmt::format("flip_image: map size {}x{} is empty", width, height));
  if (map.size() != static_cast<std::size_t>(width) * height)
    throw InputError(fmt::format("flip_image: map has {} values, {}x{} needs {}", map.size(), width,
                                 height, static_cast<std::size_t>(width) * height));
  Image out(width, height);
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const float v = map[static_cast<std::size_t>(y) * width + x];
      const int i = std::isfinite(v)
                        ? static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f))
                        : 255;
      std::uint8_t* p = out.px(x, y);
      p[0] = detail::kMagma[i][0], p[1] = detail::kMagma[i][1], p[2] = detail::kMagma[i][2],
      p[3] = 255;
    }
  });
  return out;
}

}  // namespace terrasprite::quality
