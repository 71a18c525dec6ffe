// SPDX-License-Identifier: MIT
// Fuzz target: the glTF loader, binary (.glb) or JSON (.gltf) by the first
// byte ('g' of "glTF" = binary). Bad input must end in InputError.
#include "fuzz_model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_model_file(data, size, size > 0 && data[0] == 'g' ? ".glb" : ".gltf");
}
