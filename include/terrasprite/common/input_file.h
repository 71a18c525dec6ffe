// SPDX-License-Identifier: MIT
// Reading a text file the user named (a scene, a script, a recorded path).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace terrasprite {

/// The whole of `path`, a `what` the user named (e.g. "scene file"). Throws
/// InputError naming `path` when it does not exist, is a directory or
/// another non-regular file, is larger than `max_bytes`, or cannot be read.
std::string read_input_text(const std::string& path, std::string_view what,
                            std::uintmax_t max_bytes = std::uintmax_t(256) << 20);

}  // namespace terrasprite
