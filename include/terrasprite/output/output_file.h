// SPDX-License-Identifier: MIT
// Single-file outputs (a --json file, a difference image): checked before the
// work starts, written beside the target under a temporary name and renamed
// into place when complete, never replacing a file terrasprite did not write.
#pragma once
#include <functional>
#include <string>
#include <string_view>

namespace terrasprite {

/// "terrasprite <version>": the `generator` value of every JSON it writes and
/// the content of an output directory's marker file.
std::string generator_name();

/// What may be replaced at a target path that already exists.
struct OutputPolicy {
  bool overwrite = false;  ///< replace any regular file (never a directory or device)
};

/// Throws InputError naming `path` unless a single file can be written there
/// now: the parent is an existing, writable directory (proved by creating and
/// removing a temporary file in it), and `path` is absent or a regular file
/// that terrasprite wrote (a JSON object whose "generator" names terrasprite,
/// a PNG whose Software text is kPngSoftware, an MP4 whose metadata holds
/// generator_name()) or `policy.overwrite` is set. Directories, devices, FIFOs and symbolic
/// links are always refused. Call it for every output file before any work.
void check_output_file(const std::string& path, OutputPolicy policy);

/// A fresh file, created exclusively beside `target` as `.NAME.tmp-XXXXXX`
/// (never a name the user may own); its path, or "" with errno set.
std::string create_temp_beside(const std::string& target);

/// Checks `path` as above, calls `write(tmp)` to write the whole file at a
/// temporary name in the same directory, then renames it onto `path`. On any
/// failure (or an interrupt) the temporary file is removed and the target is
/// untouched. Throws InputError naming `path`.
void write_output_file(const std::string& path, OutputPolicy policy,
                       const std::function<void(const std::string& tmp)>& write);

/// write_output_file with the whole content in memory (JSON, text).
void write_output_file(const std::string& path, OutputPolicy policy, std::string_view content);

}  // namespace terrasprite
