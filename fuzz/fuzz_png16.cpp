// SPDX-License-Identifier: MIT
// Fuzz target: PNG heights (16-bit grey, terrain-RGB, Terrarium) and the drape
// image loader, on bytes held in GDAL's in-memory filesystem. The first byte
// picks the path; bad input must end in InputError.
#include <cpl_vsi.h>

#include <cstdint>
#include <string>

#include "terrasprite/terrain/image_io.h"
#include "terrasprite/common/error.h"
#include "terrasprite/common/image.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/terrain/dem_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int mode = data[0] % 4;
  const std::string name = "/vsimem/fuzz.png";
  VSILFILE* f = VSIFileFromMemBuffer(name.c_str(), const_cast<GByte*>(data + 1), size - 1, FALSE);
  if (!f) return 0;
  VSIFCloseL(f);
  try {
    if (mode == 3) {
      terrasprite::load_image(name);
    } else {
      terrasprite::TerrainOptions o;
      o.dem = name;
      o.encoding = mode == 1   ? terrasprite::HeightEncoding::kTerrainRgb
                   : mode == 2 ? terrasprite::HeightEncoding::kTerrarium
                               : terrasprite::HeightEncoding::kAuto;
      terrasprite::load_dem(o);
    }
  } catch (const terrasprite::InputError&) {
  }
  VSIUnlink(name.c_str());
  return 0;
}
