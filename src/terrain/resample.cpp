// SPDX-License-Identifier: MIT
#include <tbb/parallel_for.h>

#include "terrasprite/terrain/resample.h"

namespace terrasprite {

Heightfield resample_heightfield(const Heightfield& src, int width, int height) {
  Heightfield out = src;
  out.width = width;
  out.height = height;
  // Same extent, new sample count: corner samples stay on the corners.
  out.spacing_x = width > 1 ? src.extent_x() / (width - 1) : src.spacing_x;
  out.spacing_y = height > 1 ? src.extent_y() / (height - 1) : src.spacing_y;
  out.heights.assign(static_cast<std::size_t>(width) * height, 0.f);
  out.resampled_to = std::make_pair(width, height);
  if (!out.resampled_from) out.resampled_from = std::make_pair(src.width, src.height);
  tbb::parallel_for(0, height, [&](int j) {
    for (int i = 0; i < width; ++i) out.at(i, j) = src.sample(out.world_x(i), out.world_y(j));
  });
  return out;
}

}  // namespace terrasprite
