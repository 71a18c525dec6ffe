// SPDX-License-Identifier: MIT
#include "terrasprite/output/output_dir.h"

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>

#include "terrasprite/common/error.h"
#include "terrasprite/output/interrupt_cleanup.h"

namespace terrasprite {
namespace {

namespace fs = std::filesystem;

fs::path normalised(const std::string& dir) {
  fs::path p(dir);
  if (p.filename().empty() && p.has_parent_path())
    p = p.parent_path();  // "out/demo/" -> "out/demo"
  return p;
}

bool has_marker(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / kOutputMarker, ec);
}

bool is_empty_dir(const fs::path& dir) {
  std::error_code ec;
  return fs::is_empty(dir, ec) && !ec;
}

// `a` equals `b` or is one of its ancestors (both canonical).
bool is_ancestor_or_self(const fs::path& a, const fs::path& b) {
  auto [ai, bi] = std::mismatch(a.begin(), a.end(), b.begin(), b.end());
  return ai == a.end();
}

void check_location(const std::string& dir, const fs::path& p) {
  const fs::path leaf = p.filename();
  if (leaf == "." || leaf == ".." || p.empty())
    throw InputError(
        fmt::format("{}: refusing to write output to '.' or '..'; name a new directory", dir));
  std::error_code ec;
  const fs::path canon = fs::weakly_canonical(fs::absolute(p, ec), ec);
  if (ec) throw InputError(fmt::format("{}: cannot resolve the path ({})", dir, ec.message()));
  if (canon == canon.root_path())
    throw InputError(fmt::format("{}: refusing to write output to the root directory", dir));
  const fs::path cwd = fs::current_path(ec);
  if (!ec && is_ancestor_or_self(canon, fs::weakly_canonical(cwd, ec)))
    throw InputError(fmt::format(
        "{}: is the working directory or one of its ancestors; name a new directory", dir));
}

// What sits at `p` may be replaced by a new output (or nothing sits there).
void check_existing(const std::string& dir, const fs::path& p, OutputPolicy policy,
                    const char* what) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (!fs::exists(st)) return;
  if (fs::is_symlink(st))
    throw InputError(fmt::format("{}: {} is a symbolic link; refusing to replace it", dir, what));
  if (!fs::is_directory(st))
    throw InputError(fmt::format(
        "{}: {} exists and is not a directory (a file, device or FIFO); refusing to replace it",
        dir, what));
  if (has_marker(p) || is_empty_dir(p) || policy.overwrite) return;
  throw InputError(fmt::format(
      "{}: {} exists and is not a terrasprite output (no {} marker); pass --overwrite to replace "
      "it",
      dir, what, kOutputMarker));
}

void check_partial(const std::string& dir, const fs::path& partial, OutputPolicy policy) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(partial, ec))) return;
  const bool ours = fs::is_directory(fs::symlink_status(partial, ec)) && has_marker(partial);
  if (!(policy.overwrite && ours))
    throw InputError(fmt::format(
        "{}: {} already exists (another run writing, or an interrupted one); remove it{}", dir,
        partial.string(), ours ? " or pass --overwrite" : ""));
}

fs::path partial_of(const fs::path& final_path) {
  fs::path p = final_path;
  p += ".partial";
  return p;
}

}  // namespace

void OutputDir::check(const std::string& dir, OutputPolicy policy) {
  if (dir.empty()) throw InputError("output directory: empty name");
  const fs::path p = normalised(dir);
  check_location(dir, p);
  check_existing(dir, p, policy, "it");
  check_partial(dir, partial_of(p), policy);
}

OutputDir::OutputDir(const std::string& dir, OutputPolicy policy) : policy_(policy) {
  check(dir, policy);
  final_ = normalised(dir);
  partial_ = partial_of(final_);
  std::error_code ec;
  if (fs::exists(fs::symlink_status(partial_, ec))) fs::remove_all(partial_, ec);  // ours: checked
  ec.clear();
  if (final_.has_parent_path()) fs::create_directories(final_.parent_path(), ec);
  // create_directory fails if the path appeared meanwhile: we own what we create.
  if (ec || !fs::create_directory(partial_, ec) || ec)
    throw InputError(fmt::format("{}: cannot create output directory {} ({})", dir,
                                 partial_.string(), ec ? ec.message() : "it already exists"));
  guard_ = std::make_unique<CleanupOnInterrupt>(partial_);
  std::ofstream marker(partial_ / kOutputMarker);
  marker << generator_name() << "\n";
  marker.close();
  if (!marker)
    throw InputError(
        fmt::format("{}: cannot write in output directory {}", dir, partial_.string()));
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
  run_unless_interrupted([&] { fs::create_directories(p.parent_path(), ec); });
  return p.string();
}

void OutputDir::commit() {
  check_existing(final_.string(), final_, policy_, "it");  // may have appeared during the run
  guard_->release_after([&] {
    std::error_code ec;
    fs::path old;
    if (fs::exists(fs::symlink_status(final_, ec))) {
      // Move the previous output aside first: a directory cannot be renamed over a
      // non-empty one, and the new output must be in place before the old one goes.
      old = final_;
      old += fmt::format(".replaced-{}", getpid());
      fs::rename(final_, old, ec);
      if (ec)
        throw InputError(fmt::format("{}: cannot move the previous output aside ({})",
                                     final_.string(), ec.message()));
    }
    fs::rename(partial_, final_, ec);
    if (ec) {
      std::error_code ignored;
      if (!old.empty()) fs::rename(old, final_, ignored);
      throw InputError(fmt::format("{}: cannot move finished output into place ({})",
                                   final_.string(), ec.message()));
    }
    committed_ = true;
    if (!old.empty()) fs::remove_all(old, ec);
  });
}

}  // namespace terrasprite
