// SPDX-License-Identifier: MIT
// Output directories that never look complete before they are.
#pragma once
#include <filesystem>
#include <string>

namespace terrasprite {

/// Writes go into `DIR.partial`; commit() renames it to `DIR` (replacing an
/// older `DIR`). Destroyed without commit(), the partial directory is removed,
/// so a failed or interrupted run leaves nothing that looks complete.
/// Throws InputError naming the directory when it cannot be created.
class OutputDir {
 public:
  explicit OutputDir(const std::string& dir);
  ~OutputDir();
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  /// Path of a file inside the partial directory (creating sub-directories).
  std::string file(const std::string& relative) const;
  const std::filesystem::path& partial() const { return partial_; }
  const std::filesystem::path& final_path() const { return final_; }
  void commit();

 private:
  std::filesystem::path final_, partial_;
  bool committed_ = false;
};

}  // namespace terrasprite
