// SPDX-License-Identifier: MIT
// Fuzz target: the camera-path JSON reader, sampled over a small terrain (the
// clip-plane fit samples the heights). Bad input must end in InputError.
#include <cstdint>
#include <string_view>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/synth.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const terrasprite::Heightfield terrain = [] {
    terrasprite::SynthOptions s;
    s.size = 33;
    return terrasprite::synthesize_terrain(s);
  }();
  try {
    terrasprite::path_from_json(std::string_view(reinterpret_cast<const char*>(data), size),
                                "fuzz.json", terrain, 8, 1.5);
  } catch (const terrasprite::InputError&) {
  }
  return 0;
}
