// SPDX-License-Identifier: MIT
// The COG writer's one mechanism, shared by the in-memory and the strip-wise
// writers: GDAL's COG driver is CreateCopy-only and builds area-aligned
// overviews of its own, so it is handed a VRT whose raster is level 0 and
// whose <Overview> elements are our vertex-aligned levels (in memory: MEM
// datasets over our buffers; strip-wise: temporary tiled GeoTIFFs), and told
// to keep them (OVERVIEWS=FORCE_USE_EXISTING): the file's overview k is
// level k + 1 exactly, whatever its size.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite {

/// One level of a COG's source: a GDAL dataset name and its size.
struct LevelSource {
  std::string name;  ///< a MEM::: string (mem_source) or a raster file
  int w = 0, h = 0;
};

/// A MEM dataset name over `data`: w x h pixels of `type`, `bands`
/// byte-interleaved bands at `pixel_bytes` apart (packed RGBA: 4 bands of
/// 1 byte, 4 bytes a pixel). `data` must outlive every use of the name.
std::string mem_source(const void* data, int w, int h, const char* type, int bands,
                       int pixel_bytes);

/// Throws InputError naming a bad field of `o`.
void check_write_options(const TileWriteOptions& o);

/// Writes DIR/height.tif (Float32, band 1 of each height source),
/// DIR/bound.tif (Float32, no georeferencing: its cells sit between samples)
/// and DIR/color.tif (bands 1..3 of each colour source) as COGs whose
/// overviews are levels 1.. of each list. Throws InputError naming a file
/// GDAL could not write.
void write_level_cogs(const std::vector<LevelSource>& heights,
                      const std::vector<LevelSource>& colors,
                      const std::vector<LevelSource>& bounds,
                      const std::optional<GeoTransform>& geo, const std::string& dir,
                      const TileWriteOptions& o);

}  // namespace terrasprite
