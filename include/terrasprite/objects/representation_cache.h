// SPDX-License-Identifier: MIT
// The on-disk cache of a model's representations (its LOD chain and its
// impostor textures, read back after their first build), so a scene's
// second run does not simplify or capture again. Keyed like the quality
// tables: the model file's bytes (and its texture's), the model options,
// each representation's build parameters and a format version, so a changed
// input never reads a stale entry.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/model.h"

namespace terrasprite {

/// 64-bit FNV-1a of `bytes`, continuing from `h`.
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 1469598103934665603ull);

/// The whole file. Throws InputError naming `path` when it cannot be read.
std::string read_file_bytes(const std::filesystem::path& path);

/// Writes `bytes` to `file` through a temporary file of this process in the
/// same folder and a rename, so a reader (another process sharing the cache)
/// sees the old file or the new one, never half of one. Creates the folder.
/// Returns false (nothing left behind) when any step fails.
bool write_file_atomically(const std::filesystem::path& file, std::string_view bytes);

/// The objects cache folder: cache_root() (terrasprite/common/cache_dir.h) / objects.
std::string default_cache_dir();

/// FNV-1a of the model file's bytes, then of `options.texture`'s (if any).
/// Throws InputError when a file cannot be read.
std::uint64_t model_files_hash(const std::string& model_file, const ModelOptions& options);

/// Hex key of a model's source: FNV-1a of the model file's bytes and of
/// `options.texture`'s, and the options themselves. Throws InputError when a
/// file cannot be read.
std::string model_source_key(const std::string& model_file, const ModelOptions& options);

/// What an enabled cache did, for reports (a disabled one counts nothing).
struct RepresentationCacheStats {
  int hits = 0;      ///< entries read
  int misses = 0;    ///< entries built (and written, when enabled)
  int rejected = 0;  ///< entries present but unreadable (truncated, corrupt): rebuilt
  double read_ms = 0, build_ms = 0;
};

/// One model's entries under a folder. Copyable; a default-constructed one
/// is disabled (every lookup misses, nothing is written). Files are
/// `<dir>/<stem>-<key>-<what>.rep`: a header (magic, format version, payload
/// size) and the payload as one zstd frame with its content checksum. An entry that fails any
/// check is reported on stderr and treated as missing; its file is replaced
/// by the rebuilt entry (the folder holds only files this cache wrote).
class RepresentationCache {
 public:
  RepresentationCache() = default;
  /// `dir` empty: disabled. `key`: model_source_key(); `stem`: a readable
  /// name for the files (the model file's stem).
  RepresentationCache(std::filesystem::path dir, std::string key, std::string stem);

  bool enabled() const { return !dir_.empty(); }
  /// The payload stored under `what` (e.g. "relief-128"), if present, intact
  /// and accepted by `check` (which returns nullptr, or the problem with a
  /// payload its caller cannot use: reported and counted like a damaged one).
  std::optional<std::string> read(
      const std::string& what,
      const std::function<const char*(std::string_view)>& check = nullptr) const;
  /// Stores `payload` under `what`; a failure is a warning, never an error.
  void write(const std::string& what, std::string_view payload) const;
  std::filesystem::path file(const std::string& what) const;

  /// Counters, shared by the copies of one cache (mutable through const: a
  /// lookup is logically const).
  RepresentationCacheStats& stats() const { return *stats_; }

 private:
  std::filesystem::path dir_;
  std::string key_, stem_;
  std::shared_ptr<RepresentationCacheStats> stats_ = std::make_shared<RepresentationCacheStats>();
};

/// The LOD chain as bytes and back. deserialize returns nullopt for bytes
/// that are not a chain serialize wrote (sizes, index ranges, part ranges).
std::string serialize_lod_chain(const std::vector<LodLevel>& chain);
std::optional<std::vector<LodLevel>> deserialize_lod_chain(std::string_view bytes,
                                                           std::size_t materials);

/// The cache entry name of the chain build_lod_chain makes with `options` (and
/// the algorithm's version): what cached_lod_chain reads and writes, and part
/// of the key of a quality table measured on that chain.
std::string lod_chain_key(const LodOptions& options);

/// build_lod_chain(model, options), read from `cache` when an entry for these
/// options is there, else built and stored.
std::vector<LodLevel> cached_lod_chain(const Model& model, const LodOptions& options,
                                       const RepresentationCache& cache);

}  // namespace terrasprite
