// SPDX-License-Identifier: MIT
// One rendered frame: colour, depth and what it cost.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "terrasprite/camera.h"
#include "terrasprite/image.h"

namespace terrasprite {

/// A rendered image with its linear depth and timings. Rows top to bottom.
struct Frame {
  Image color;  ///< RGBA8, alpha 255
  std::vector<float>
      depth;        ///< width*height, metres along the view axis; +inf = sky; empty if not read
  double ms = 0.0;  ///< rendering work, wall clock, pipeline drained (read-back excluded)
  double gpu_ms = -1.0;     ///< GL timer-query time, or -1 when unavailable
  long long triangles = 0;  ///< triangles submitted (0 for non-raster renderers)
  std::string cls;          ///< frame class: full, lod, key, sprite, voxel, warp
  /// The camera the frame was rendered with (its view() and projection(),
  /// near/far included), so a later stage (warp, quality) can reproject it.
  Camera camera;

  static constexpr float kSky = std::numeric_limits<float>::infinity();
  int width() const { return color.width; }
  int height() const { return color.height; }
};

}  // namespace terrasprite
