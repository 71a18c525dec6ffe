// SPDX-License-Identifier: MIT
#include "terrasprite/common/cache_dir.h"

#include <cstdlib>
#include <filesystem>

namespace terrasprite {

std::string cache_root(bool* from_env) {
  namespace fs = std::filesystem;
  if (from_env) *from_env = false;
  if (const char* d = std::getenv("TERRASPRITE_CACHE"); d && *d) {
    if (from_env) *from_env = true;
    return d;
  }
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d)
    return (fs::path(d) / "terrasprite").string();
  if (const char* d = std::getenv("HOME"); d && *d)
    return (fs::path(d) / ".cache" / "terrasprite").string();
  return (fs::temp_directory_path() / "terrasprite-cache").string();
}

}  // namespace terrasprite
