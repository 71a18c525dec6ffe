// SPDX-License-Identifier: MIT
// Fuzz target: the Wavefront OBJ loader. Bad input must end in InputError.
#include "fuzz_model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz_model_file(data, size, ".obj");
}
