// SPDX-License-Identifier: MIT
// Fuzz target: the height-raster loader (GDAL, every driver it registers) on
// bytes held in GDAL's in-memory filesystem. Bad input must end in InputError.
#include <cpl_vsi.h>

#include <cstdint>
#include <string>

#include "terrasprite/common/error.h"
#include "terrasprite/terrain/terrain.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string name = "/vsimem/fuzz_dem";
  VSILFILE* f = VSIFileFromMemBuffer(name.c_str(), const_cast<GByte*>(data), size, FALSE);
  if (!f) return 0;
  VSIFCloseL(f);
  terrasprite::TerrainOptions o;
  o.dem = name;
  try {
    terrasprite::load_terrain(o);
  } catch (const terrasprite::InputError&) {
  }
  VSIUnlink(name.c_str());
  return 0;
}
