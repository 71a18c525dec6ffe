// SPDX-License-Identifier: MIT
// The on-disk cache of a model's representations (its LOD chain and its
// impostor textures, read back after their first build), so a scene's
// second run does not simplify or capture again. Keyed like the quality
// tables: the loaded model's content (so every file it came from), the model
// options, each representation's build parameters and a format version, all
// recorded in the entry and compared on reading, so a changed input, another
// model's entry or a damaged one is never read.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "terrasprite/common/cache_entry.h"
#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/model.h"

namespace terrasprite {

/// The objects cache folder: cache_root() (terrasprite/common/cache_dir.h) / objects.
std::string default_cache_dir();

/// FNV-1a of everything a representation is built from: the loaded model's
/// vertices, indices, parts, materials, texture pixels, scale and bounds. Its
/// source files (an OBJ's .mtl and images, a glTF's buffers and images) count
/// through what the loader made of them, so a change to any of them changes it.
std::uint64_t model_content_hash(const Model& model);

/// Hex key of a model: model_content_hash() and a digest of the options it
/// was loaded with; 32 hex digits. The model's file name and folder play no
/// part (a moved file keeps its entries).
std::string model_source_key(const Model& model, const ModelOptions& options);

/// What an enabled cache did, for reports (a disabled one counts nothing).
struct RepresentationCacheStats {
  int hits = 0;      ///< entries read
  int misses = 0;    ///< entries built (and written, when enabled)
  int rejected = 0;  ///< entries present but unreadable (truncated, corrupt): rebuilt
  double read_ms = 0, build_ms = 0;
};

/// One model's entries under a folder. Copyable; a default-constructed one
/// is disabled (every lookup misses, nothing is written). Files are
/// `<dir>/<stem>-<key>-<what>.rep`, cache entries (terrasprite/common/cache_entry.h)
/// whose key is entry_key(what): the file name is only where to look, the
/// recorded key decides. An entry that fails any check (another key, a
/// checksum, its size, `check`) is reported on stderr in one line and treated
/// as missing; its file is replaced by the rebuilt entry (the folder holds
/// only files this cache wrote).
class RepresentationCache {
 public:
  RepresentationCache() = default;
  /// `dir` empty: disabled. `key`: model_source_key(); `stem`: a readable
  /// name for the files (the model file's stem).
  RepresentationCache(std::filesystem::path dir, std::string key, std::string stem);

  bool enabled() const { return !dir_.empty(); }
  /// The payload stored under `what` (e.g. "relief-128"), if present, of
  /// this key, intact, at most `max_size` bytes (a larger claim is refused
  /// before anything is allocated) and accepted by `check` (which returns
  /// nullptr, or the problem with a payload its caller cannot use: reported
  /// and counted like a damaged one).
  std::optional<std::string> read(
      const std::string& what, std::uint64_t max_size,
      const std::function<const char*(std::string_view)>& check = nullptr) const;
  /// Stores `payload` under `what`; a failure is a warning, never an error.
  void write(const std::string& what, std::string_view payload) const;
  std::filesystem::path file(const std::string& what) const;
  /// The key recorded in and required of the entry `what`: the format
  /// version, the model's key and `what` (the build parameters).
  std::string entry_key(const std::string& what) const;

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

/// The most bytes serialize_lod_chain can make of a chain that
/// build_lod_chain(model, options) builds: a larger entry is not read.
std::uint64_t lod_chain_max_bytes(const Model& model, const LodOptions& options);

/// build_lod_chain(model, options), read from `cache` when an entry for these
/// options is there, else built and stored.
std::vector<LodLevel> cached_lod_chain(const Model& model, const LodOptions& options,
                                       const RepresentationCache& cache);

}  // namespace terrasprite
