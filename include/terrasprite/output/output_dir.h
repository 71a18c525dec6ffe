// SPDX-License-Identifier: MIT
// Output directories that never look complete before they are, and never
// replace anything terrasprite did not create.
#pragma once
#include <filesystem>
#include <memory>
#include <string>

#include "terrasprite/output/output_file.h"

namespace terrasprite {

class CleanupOnInterrupt;

/// The marker file every output directory holds ("terrasprite <version>").
inline constexpr const char* kOutputMarker = ".terrasprite-output";

/// Writes go into `DIR.partial`, created fresh by this object (with the
/// marker file); commit() renames it to `DIR`. Destroyed without commit(),
/// or on SIGINT/SIGTERM once install_interrupt_cleanup() ran, the partial
/// directory is removed, so a failed or interrupted run leaves nothing that
/// looks complete.
///
/// Refused up front with InputError naming `dir`, touching nothing: an empty
/// name, `.` or `..` as the last component, the root, the working directory or
/// any of its ancestors, an existing non-directory (file, device, FIFO,
/// socket, symbolic link), an existing non-empty directory without the marker
/// (unless `policy.overwrite`), and an existing `DIR.partial` (another run's,
/// or an interrupted one; with `policy.overwrite` it is removed only if it
/// holds the marker). commit() checks `DIR` again before replacing it.
class OutputDir {
 public:
  explicit OutputDir(const std::string& dir, OutputPolicy policy = {});
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  /// Path of a file inside the partial directory (creating sub-directories).
  std::string file(const std::string& relative) const;
  const std::filesystem::path& partial() const { return partial_; }
  const std::filesystem::path& final_path() const { return final_; }
  void commit();

  /// The checks of the constructor alone: throws InputError naming `dir`
  /// when terrasprite may not write an output directory there.
  static void check(const std::string& dir, OutputPolicy policy);

 private:
  std::filesystem::path final_, partial_;
  OutputPolicy policy_;
  std::unique_ptr<CleanupOnInterrupt> guard_;
  bool committed_ = false;
};

}  // namespace terrasprite
