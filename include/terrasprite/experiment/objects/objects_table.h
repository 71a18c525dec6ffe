// SPDX-License-Identifier: MIT
// `objects table`: a model's quality table (quality_table.h), read from the
// table cache when these inputs were measured before, else measured and stored.
#pragma once
#include <filesystem>
#include <functional>
#include <string>

#include "terrasprite/objects/model.h"
#include "terrasprite/objects/quality_table.h"
#include "terrasprite/objects/representation_cache.h"

namespace terrasprite {

struct ObjectsTableOptions {
  std::string model_file;  ///< .obj, .gltf or .glb
  ModelOptions model;
  TableOptions table;
  /// Folder of the table and representation caches; empty: default_cache_dir().
  std::string cache_dir;
  /// false: measure from scratch, reading and storing nothing.
  bool use_cache = true;
  /// Called per view measured (done, total); not called for a cached table.
  std::function<void(int, int)> progress;
};

struct ObjectsTableResult {
  QualityTable table;
  bool cached = false;  ///< read from the table cache (not measured by this run)
  /// The representation cache's counters while measuring (all 0 when cached
  /// or when use_cache is false).
  RepresentationCacheStats representation_cache;
  std::filesystem::path cache_file;  ///< the table's cache file (empty when use_cache is false)
};

/// Loads the model, then reads its table from the cache or measures it (in
/// its own GlContext, on the LOD chain of LodOptions{}) and stores it.
/// Throws InputError (one line naming the file) for a model that cannot be
/// loaded, and what measure_quality_table throws for bad options.
ObjectsTableResult run_objects_table(const ObjectsTableOptions& options);

}  // namespace terrasprite
