// SPDX-License-Identifier: MIT
// Image file I/O: any raster GDAL or stb reads in, PNG (8-bit RGBA, 16-bit grey) out.
#pragma once
#include <cstdint>
#include <span>
#include <string>

#include "terrasprite/common/image.h"

namespace terrasprite {

/// Loads any image GDAL or stb reads (PNG, JPEG, GeoTIFF incl. RGBA, ...).
/// Grey is replicated to RGB, RGB gets alpha 255, 16-bit samples are scaled to
/// 8 bits (v * 255 / 65535). A georeferenced file fills `Image::geo`.
/// Throws InputError naming `path` when it is missing, unreadable or empty, or
/// larger than 16384 pixels a side (checked from the header, before decoding).
Image load_image(const std::string& path);

/// Writes an RGBA8 image as PNG (alpha kept), tagged Software = kPngSoftware.
/// Throws InputError naming `path` when any byte cannot be written (a full
/// disk, a file-size limit).
void save_png(const Image& image, const std::string& path);

/// Writes a single-channel 16-bit PNG (row 0 on top). Throws InputError on failure.
void save_png16(std::span<const std::uint16_t> grey, int width, int height,
                const std::string& path);

}  // namespace terrasprite
