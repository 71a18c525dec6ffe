// SPDX-License-Identifier: MIT
#include "terrasprite/common/input_file.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "terrasprite/common/error.h"

namespace terrasprite {

std::string read_input_text(const std::string& path, std::string_view what,
                            std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw InputError(fmt::format("{}: no such {}", path, what));
  if (fs::is_directory(st))
    throw InputError(fmt::format("{}: is a directory, not a {}", path, what));
  if (!fs::is_regular_file(st))
    throw InputError(fmt::format("{}: is not a regular file (a {} is expected)", path, what));
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes)
    throw InputError(fmt::format("{}: {} bytes, more than a {} may hold ({} MB)", path, size, what,
                                 max_bytes >> 20));
  std::ifstream in(path, std::ios::binary);
  std::string text;
  if (in) text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw InputError(fmt::format("{}: cannot read the {}", path, what));
  return text;
}

}  // namespace terrasprite
