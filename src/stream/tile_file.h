// SPDX-License-Identifier: MIT
// One thread's view of a tiled terrain on disk: its own GDAL handles (GDAL
// datasets are not thread-safe) and windowed reads of one tile of one level,
// never the whole raster.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "terrasprite/stream/tiled_terrain.h"

typedef void* GDALDatasetH;

namespace terrasprite {

/// A tile's samples as read: the storage a TileBlock views.
struct TileData {
  int level = 0, tx = 0, ty = 0;
  TileBlock block;  ///< views into the vectors below
  std::vector<float> height;
  std::vector<std::uint32_t> color;
  std::vector<float> bound;
  std::size_t bytes() const {
    return height.size() * 4 + color.size() * 4 + bound.size() * 4 + sizeof(TileData);
  }
};

/// The window of tile (tx, ty) of `level`: first sample, samples across and
/// down (cells + 1), as TileBlock states it.
void tile_window(const TileSetInfo& set, int level, int tx, int ty, int& x0, int& y0, int& w,
                 int& h);
/// Bytes a tile of `level` takes once read (its storage; see TileData::bytes).
std::size_t tile_bytes(const TileSetInfo& set, int level, int tx, int ty);

/// Tile (tx, ty) of fine level `level` of the renderer's grid as the fine
/// window set `fine`'s own tile (changed in place); false outside the window
/// or where the tile holds no inset data (the base serves it).
bool fine_window_tile(const TileSetInfo& fine, int level, int& tx, int& ty);

class TileFile {
 public:
  explicit TileFile(const TileSetInfo& set);  ///< throws InputError naming a file
  ~TileFile();
  TileFile(const TileFile&) = delete;
  TileFile& operator=(const TileFile&) = delete;
  /// Reads tile (tx, ty) of `level` into `out` (block views set); false and
  /// `error` set when GDAL fails.
  bool read(int level, int tx, int ty, TileData& out, std::string& error);
  /// A whole level (height, colour where it has samples, bound) as one tile.
  bool read_level(int level, TileData& out, std::string& error);
  /// The heights of a whole sample level (row-major, level_w x level_h).
  bool read_level_heights(int level, std::vector<float>& out, std::string& error);

 private:
  bool read_window(int level, int x0, int y0, int w, int h, TileData& out, std::string& error);
  /// read_window's reads from a `terrasprite tile` directory (vectors only).
  bool read_tiles_window(int level, int x0, int y0, int w, int h, TileData& out,
                         std::string& error);
  const TileSetInfo& set_;
  GDALDatasetH height_ = nullptr, color_ = nullptr, bound_ = nullptr;
};

}  // namespace terrasprite
