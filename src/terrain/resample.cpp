// SPDX-License-Identifier: MIT
#include "terrasprite/terrain/resample.h"

#include <tbb/parallel_for.h>

#include <cmath>

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
  if (!src.voids.empty()) {  // the nearest source sample's flag
    out.voids.assign(out.heights.size(), 0);
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i) {
        const long si = width > 1 ? std::lround(double(i) * (src.width - 1) / (width - 1)) : 0;
        const long sj = height > 1 ? std::lround(double(j) * (src.height - 1) / (height - 1)) : 0;
        out.voids[std::size_t(j) * width + i] = src.voids[std::size_t(sj) * src.width + si];
      }
  }
  return out;
}

}  // namespace terrasprite
