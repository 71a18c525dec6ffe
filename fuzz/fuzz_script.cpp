// SPDX-License-Identifier: MIT
// Fuzz target: the viewer's input script parser (`view --script`). Bad input
// must end in InputError.
#include <cstdint>
#include <string_view>

#include "terrasprite/common/error.h"
#include "viewer/input_event.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    terrasprite::viewer::parse_input_script(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const terrasprite::InputError&) {
  }
  return 0;
}
