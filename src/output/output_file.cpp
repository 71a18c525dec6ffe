// SPDX-License-Identifier: MIT
#include "terrasprite/output/output_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"
#include "terrasprite/output/interrupt_cleanup.h"

#ifndef TERRASPRITE_VERSION
#define TERRASPRITE_VERSION "unknown"
#endif

namespace terrasprite {
namespace {

namespace fs = std::filesystem;

// A JSON object whose "generator" names terrasprite: a file we wrote.
bool written_by_terrasprite(const fs::path& p) {
  std::ifstream in(p);
  if (!in) return false;
  nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("generator") || !j["generator"].is_string()) return false;
  return j["generator"].get<std::string>().rfind("terrasprite", 0) == 0;
}

fs::path parent_of(const fs::path& p) {
  fs::path parent = p.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

// A fresh, exclusively created file beside `target`; its path, or "" with errno set.
std::string create_temp_beside(const fs::path& target) {
  std::string tmpl =
      (parent_of(target) / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  int fd = mkstemp(tmpl.data());
  if (fd < 0) return {};
  close(fd);
  return tmpl;
}

}  // namespace

std::string generator_name() {
  return std::string("terrasprite ") + TERRASPRITE_VERSION;
}

void check_output_file(const std::string& path, OutputPolicy policy) {
  if (path.empty()) throw InputError("output file: empty name");
  const fs::path p(path);
  if (p.filename().empty() || p.filename() == "." || p.filename() == "..")
    throw InputError(fmt::format("{}: names a directory, not an output file", path));
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (fs::exists(st)) {
    if (fs::is_directory(st))
      throw InputError(fmt::format("{}: is a directory, not an output file", path));
    if (fs::is_symlink(st))
      throw InputError(fmt::format("{}: is a symbolic link; refusing to replace it", path));
    if (!fs::is_regular_file(st))
      throw InputError(
          fmt::format("{}: is a device, FIFO or socket; refusing to replace it", path));
    if (!policy.overwrite && !written_by_terrasprite(p))
      throw InputError(fmt::format(
          "{}: exists and was not written by terrasprite; pass --overwrite to replace it", path));
  }
  const fs::path dir = parent_of(p);
  if (!fs::is_directory(dir, ec))
    throw InputError(fmt::format("{}: directory {} does not exist", path, dir.string()));
  const std::string probe = create_temp_beside(p);
  if (probe.empty())
    throw InputError(
        fmt::format("{}: cannot write in {} ({})", path, dir.string(), std::strerror(errno)));
  fs::remove(probe, ec);
}

void write_output_file(const std::string& path, OutputPolicy policy,
                       const std::function<void(const std::string& tmp)>& write) {
  check_output_file(path, policy);
  const std::string tmp = create_temp_beside(path);
  if (tmp.empty())
    throw InputError(fmt::format("{}: cannot write ({})", path, std::strerror(errno)));
  CleanupOnInterrupt guard(tmp);
  std::error_code ec;
  try {
    write(tmp);
    // mkstemp creates 0600; an output file gets the usual umask-derived mode.
    const mode_t mask = umask(0);
    umask(mask);
    chmod(tmp.c_str(), 0666 & ~mask);
    guard.release_after([&] {
      fs::rename(tmp, path, ec);
      if (ec) throw InputError(fmt::format("{}: cannot move into place ({})", path, ec.message()));
    });
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

void write_output_file(const std::string& path, OutputPolicy policy, std::string_view content) {
  write_output_file(path, policy, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(content.data(), std::streamsize(content.size()));
    out.close();
    if (!out) throw InputError(fmt::format("{}: write failed (disk full?)", path));
  });
}

}  // namespace terrasprite
