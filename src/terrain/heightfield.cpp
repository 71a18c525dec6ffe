// SPDX-License-Identifier: MIT
#include "terrasprite/terrain/heightfield.h"

#include <algorithm>
#include <cmath>

#include "terrain/grid_sample.h"

namespace terrasprite {

const char* to_string(NodataFill f) {
  switch (f) {
    case NodataFill::kGdal:
      return "gdal";
    case NodataFill::kNone:
      return "none";
    default:
      return "amle";
  }
}

float Heightfield::sample(double x, double y) const {
  return detail::sample_grid(width, height, spacing_x, spacing_y, x, y,
                             [this](int i, int j) { return at(i, j); });
}

float Heightfield::min_height() const {
  return heights.empty() ? 0.f : *std::min_element(heights.begin(), heights.end());
}

float Heightfield::max_height() const {
  return heights.empty() ? 0.f : *std::max_element(heights.begin(), heights.end());
}

HeightSampler height_sampler(const Heightfield& h) {
  HeightSampler s;
  s.sample = [&h](double x, double y) { return h.sample(x, y); };
  s.width = h.width;
  s.height = h.height;
  s.spacing_x = h.spacing_x;
  s.spacing_y = h.spacing_y;
  s.min_height = h.min_height();
  s.max_height = h.max_height();
  return s;
}

}  // namespace terrasprite
