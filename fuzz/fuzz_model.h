// SPDX-License-Identifier: MIT
// The model loaders read files (tinyobjloader, tinygltf): a fuzz input is
// written to a per-process temporary file with the extension under test.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "terrasprite/common/error.h"
#include "terrasprite/objects/model.h"

inline int fuzz_model_file(const std::uint8_t* data, std::size_t size, const char* extension) {
  static const std::string path = (std::filesystem::temp_directory_path() /
                                   ("terrasprite_fuzz_" + std::to_string(getpid()) + extension))
                                      .string();
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  try {
    terrasprite::load_model(path);
  } catch (const terrasprite::InputError&) {
  }
  std::error_code ec;
  std::filesystem::remove(path, ec);
  return 0;
}
