// SPDX-License-Identifier: MIT
#include "terrasprite/output/output_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"
#include "terrasprite/common/image.h"
#include "terrasprite/output/interrupt_cleanup.h"

#ifndef TERRASPRITE_VERSION
#define TERRASPRITE_VERSION "unknown"
#endif

namespace terrasprite {
namespace {

namespace fs = std::filesystem;

std::uint32_t big_endian32(const unsigned char* b) {
  return std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | b[3];
}

// A JSON object whose "generator" names terrasprite.
bool json_written_by_terrasprite(std::ifstream& in) {
  nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("generator") || !j["generator"].is_string()) return false;
  return j["generator"].get<std::string>().rfind("terrasprite", 0) == 0;
}

// A PNG with a tEXt chunk Software = kPngSoftware before its image data.
bool png_written_by_terrasprite(std::ifstream& in) {
  const std::string tag = std::string("Software") + '\0' + kPngSoftware;
  in.seekg(8);
  for (int chunk = 0; chunk < 64; ++chunk) {
    unsigned char header[8];
    if (!in.read(reinterpret_cast<char*>(header), 8)) return false;
    const std::uint32_t length = big_endian32(header);
    const std::string type(reinterpret_cast<const char*>(header) + 4, 4);
    if (type == "IDAT" || type == "IEND") return false;
    if (type == "tEXt" && length == tag.size()) {
      std::string body(length, '\0');
      if (!in.read(body.data(), length)) return false;
      if (body == tag) return true;
      in.seekg(4, std::ios::cur);
    } else {
      in.seekg(std::streamoff(length) + 4, std::ios::cur);
    }
  }
  return false;
}

// An MP4 whose top-level moov box holds the comment the video writer puts
// there (generator_name()).
bool mp4_written_by_terrasprite(std::ifstream& in) {
  const std::string mark = generator_name();
  std::streamoff at = 0;
  for (int box = 0; box < 16; ++box) {
    unsigned char header[16];
    in.seekg(at);
    if (!in.read(reinterpret_cast<char*>(header), 8)) return false;
    std::uint64_t size = big_endian32(header);
    std::streamoff body = 8;
    if (size == 1) {  // a 64-bit size follows the type
      if (!in.read(reinterpret_cast<char*>(header + 8), 8)) return false;
      size = std::uint64_t(big_endian32(header + 8)) << 32 | big_endian32(header + 12);
      body = 16;
    }
    if (size < std::uint64_t(body)) return false;
    if (std::string(reinterpret_cast<const char*>(header) + 4, 4) == "moov") {
      std::string moov(std::min<std::uint64_t>(size - body, 64u << 20), '\0');
      in.read(moov.data(), std::streamsize(moov.size()));
      return moov.find(mark) != std::string::npos;
    }
    at += std::streamoff(size);
  }
  return false;
}

// A file terrasprite wrote: a JSON report, a PNG or an MP4 carrying its mark.
bool written_by_terrasprite(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  char magic[8] = {};
  if (!in.read(magic, 8)) return false;
  if (std::memcmp(magic, "\x89PNG\r\n\x1a\n", 8) == 0) return png_written_by_terrasprite(in);
  if (std::memcmp(magic + 4, "ftyp", 4) == 0) return mp4_written_by_terrasprite(in);
  in.seekg(0);
  return json_written_by_terrasprite(in);
}

fs::path parent_of(const fs::path& p) {
  fs::path parent = p.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

}  // namespace

std::string create_temp_beside(const std::string& target) {
  const fs::path t(target);
  std::string tmpl = (parent_of(t) / ("." + t.filename().string() + ".tmp-XXXXXX")).string();
  int fd = mkstemp(tmpl.data());
  if (fd < 0) return {};
  close(fd);
  return tmpl;
}

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
