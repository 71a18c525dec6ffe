// SPDX-License-Identifier: MIT
// Fuzz target: a tile set's tiles.json (parse_tile_set_json: the grid, the
// tile tables and their bounds, fine levels, georeferencing). Bad input must
// end in InputError.
#include <cstdint>
#include <string>

#include "stream/tile_set_json.h"
#include "terrasprite/common/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const terrasprite::TileSetInfo t = terrasprite::parse_tile_set_json(
        std::string(reinterpret_cast<const char*>(data), size), "fuzz/tiles.json");
    // What the readers do with a parsed set: walk every level's tile table.
    for (int L = 0; L < t.grid.bound_levels; ++L)
      for (float m : t.tile_max[std::size_t(L)]) (void)m;
  } catch (const terrasprite::InputError&) {
  }
  return 0;
}
