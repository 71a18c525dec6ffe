// SPDX-License-Identifier: MIT
#include "terrasprite/output_dir.h"

#include <fmt/format.h>

#include "terrasprite/error.h"

namespace terrasprite {

namespace fs = std::filesystem;

OutputDir::OutputDir(const std::string& dir) {
  if (dir.empty()) throw InputError("--out: empty directory name");
  final_ = fs::path(dir);
  if (final_.filename().empty()) final_ = final_.parent_path();  // "out/demo/" -> "out/demo"
  partial_ = final_;
  partial_ += ".partial";
  std::error_code ec;
  fs::remove_all(partial_, ec);
  fs::create_directories(partial_, ec);
  if (ec)
    throw InputError(fmt::format("{}: cannot create output directory ({})", dir, ec.message()));
}

OutputDir::~OutputDir() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(partial_, ec);
  }
}

std::string OutputDir::file(const std::string& relative) const {
  fs::path p = partial_ / relative;
  std::error_code ec;
  fs::create_directories(p.parent_path(), ec);
  return p.string();
}

void OutputDir::commit() {
  std::error_code ec;
  fs::remove_all(final_, ec);
  fs::rename(partial_, final_, ec);
  if (ec)
    throw InputError(fmt::format("{}: cannot move finished output into place ({})", final_.string(),
                                 ec.message()));
  committed_ = true;
}

}  // namespace terrasprite
