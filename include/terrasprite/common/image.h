// SPDX-License-Identifier: MIT
// RGBA8 images and read-only views on them (file I/O: terrain/image_io.h).
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace terrasprite {

/// The "Software" text of every PNG terrasprite writes (a tEXt chunk before
/// the image data): how a rerun recognises its own outputs.
inline constexpr const char* kPngSoftware = "terrasprite";

/// Affine map from pixel (column, row) to georeferenced coordinates, as GDAL's
/// geotransform: X = gt[0] + col*gt[1] + row*gt[2], Y = gt[3] + col*gt[4] + row*gt[5].
/// `wkt` is the CRS (may be empty when the file has a transform but no CRS).
struct GeoTransform {
  double gt[6] = {0, 1, 0, 0, 0, 1};
  std::string wkt;
};

/// Read-only view of 8-bit interleaved pixels. Row 0 is the top row.
/// `stride` is in bytes between rows (>= width * channels). The view never owns.
struct ImageView {
  std::span<const std::uint8_t> data;
  int width = 0;
  int height = 0;
  int stride = 0;    ///< bytes per row
  int channels = 4;  ///< 1 (grey), 3 (RGB) or 4 (RGBA)

  const std::uint8_t* row(int y) const {
    return data.data() + static_cast<std::size_t>(y) * stride;
  }
};

/// An owning RGBA8 image, rows top to bottom, tightly packed (stride = 4 * width).
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;   ///< width * height * 4 bytes
  std::optional<GeoTransform> geo;  ///< set when loaded from a georeferenced file

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0) {}

  bool empty() const { return width <= 0 || height <= 0; }
  std::uint8_t* px(int x, int y) {
    return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4;
  }
  const std::uint8_t* px(int x, int y) const {
    return rgba.data() + (static_cast<std::size_t>(y) * width + x) * 4;
  }
  ImageView view() const { return {rgba, width, height, width * 4, 4}; }
};

}  // namespace terrasprite
