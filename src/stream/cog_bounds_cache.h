// SPDX-License-Identifier: MIT
// A cache of an existing COG's max-height bounds (the one pass over the
// raster and its overviews at open, about 30 s at 16385²), so a second open
// of the same unchanged file skips it. Files live in a cache directory, never
// next to the user's COG. Each is a cache entry (terrasprite/common/cache_entry.h)
// recording its full key: the file's path, its fingerprint (device, inode,
// size, modification and change times, a hash of its first and last 64 KiB),
// the raster sizes, nodata and the held bound levels.
#pragma once
#include <string>

#include "stream/cog_source.h"

namespace terrasprite {

/// The cache directory: cache_root() (terrasprite/common/cache_dir.h) / cog-bounds.
/// `explicit_dir` says whether TERRASPRITE_CACHE chose the root.
std::string bounds_cache_dir(bool& explicit_dir);

/// What identifies a pass's result: the file and every input of the pass.
/// Empty when the file cannot be examined (nothing is then cached).
std::string bounds_cache_key(const CogInput& in, int width, int height, int bound_from,
                             int bound_levels, bool has_nodata, double nodata);

/// Reads the cached bounds for `key` from `dir` into `in` (bound, bound_from)
/// and `lo` / `hi`; false (and `in` untouched) when absent, of another key,
/// damaged, or holding bounds no pass makes (one note on stderr unless absent).
bool load_cog_bounds(const std::string& dir, const std::string& key, int width, int height,
                     int bound_from, int bound_levels, CogInput& in, float& lo, float& hi);

/// Writes them (a temporary file renamed into place); a failure is one
/// warning on stderr, never an error.
void save_cog_bounds(const std::string& dir, const std::string& key, const CogInput& in, float lo,
                     float hi);

}  // namespace terrasprite
