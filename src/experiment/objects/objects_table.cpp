// SPDX-License-Identifier: MIT
// `objects table`: the quality table of one model, cached.
#include "terrasprite/experiment/objects/objects_table.h"

#include <nlohmann/json.hpp>
#include <optional>

#include "terrasprite/gl/gl_context.h"
#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/object_renderer.h"
#include "terrasprite/objects/quality_table_cache.h"
#include "terrasprite/objects/quality_table_json.h"

namespace terrasprite {
namespace {

// Every representation rendered and scored; `cache` holds the LOD chain and
// impostors (a disabled one: all built here).
QualityTable measure(const Model& model, const ObjectsTableOptions& o,
                     const RepresentationCache& cache) {
  GlContext ctx;
  GlModel gl_model(model, cached_lod_chain(model, LodOptions{}, cache), cache);
  return measure_quality_table(gl_model, o.table, o.progress);
}

}  // namespace

ObjectsTableResult run_objects_table(const ObjectsTableOptions& o) {
  const Model model = load_model(o.model_file, o.model);
  ObjectsTableResult r;
  std::optional<QualityTable> cached;
  TableCacheEntry entry;
  if (o.use_cache) {
    entry = table_cache_entry(o.cache_dir, o.model_file, model, o.model, o.table,
                              lod_chain_key(LodOptions{}));
    r.cache_file = entry.file;
    cached = read_table_cache(entry);
  }
  r.cached = cached.has_value();
  if (r.cached) {
    r.table = std::move(*cached);
    return r;
  }
  const RepresentationCache reps =
      o.use_cache ? RepresentationCache(o.cache_dir.empty() ? default_cache_dir() : o.cache_dir,
                                        model_source_key(model, o.model),
                                        std::filesystem::path(o.model_file).stem().string())
                  : RepresentationCache{};
  r.table = measure(model, o, reps);
  r.representation_cache = reps.stats();
  if (o.use_cache) write_table_cache(entry, table_json(r.table, o.table));
  return r;
}

}  // namespace terrasprite
