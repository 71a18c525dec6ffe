// SPDX-License-Identifier: MIT
// Replacing a file that terrasprite owns (a cache entry) so that a reader,
// another process or an interrupt never sees or leaves half of one.
#pragma once
#include <filesystem>
#include <string_view>

namespace terrasprite {

/// Writes `bytes` to `file` through a temporary file of this process in the
/// same folder (`<file>.<pid>.tmp`, registered with CleanupOnInterrupt so a
/// signal removes it) and a rename, so a reader sees the old file or the new
/// one, never half of one; two processes filling the same file each rename
/// a whole file of their own. Creates the folder. Returns false (nothing
/// left behind) when any step fails; never throws for a filesystem failure.
bool replace_file_atomically(const std::filesystem::path& file, std::string_view bytes);

}  // namespace terrasprite
