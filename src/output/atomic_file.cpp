// SPDX-License-Identifier: MIT
#include "terrasprite/output/atomic_file.h"

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>

#include "terrasprite/output/interrupt_cleanup.h"

namespace terrasprite {

bool replace_file_atomically(const std::filesystem::path& file, std::string_view bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (file.has_parent_path()) fs::create_directories(file.parent_path(), ec);
  const fs::path tmp = file.string() + fmt::format(".{}.tmp", ::getpid());
  CleanupOnInterrupt guard(tmp);
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), std::streamsize(bytes.size()));
    f.close();
    if (!f) {
      fs::remove(tmp, ec);
      return false;
    }
  }
  bool renamed = false;
  guard.release_after([&] {
    fs::rename(tmp, file, ec);
    renamed = !ec;
    if (!renamed) fs::remove(tmp, ec);
  });
  return renamed;
}

}  // namespace terrasprite
