// SPDX-License-Identifier: MIT
// A scene's objects loaded, uploaded and attached to the terrain Scene.
#include "terrasprite/objects/attach_objects.h"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"
#include "terrasprite/objects/object_layout.h"
#include "terrasprite/objects/representation_cache.h"

namespace terrasprite {

std::string objects_cache_dir(const std::string& option) {
  if (option == "off") return {};
  return option.empty() ? default_cache_dir() : option;
}

void print_cache_summary(const RepresentationCacheStats& s) {
  if (s.hits + s.misses + s.rejected == 0) return;
  fmt::print(
      "objects: {} representations read from the cache in {:.0f} ms, {} built in {:.0f} ms{}\n",
      s.hits, s.read_ms, s.misses, s.build_ms,
      s.rejected ? fmt::format(" ({} unreadable entries rebuilt)", s.rejected) : "");
}

namespace {

// Every file the built-in scene names, under `models_dir`: checked before
// placing anything, as a missing data folder is the likely mistake.
void check_builtin_models(const std::string& models_dir) {
  const nlohmann::json models = nlohmann::json::parse(default_layout_json()).at("models");
  for (const auto& m : models)
    for (const char* key : {"file", "texture"})
      if (m.contains(key) && !std::filesystem::is_regular_file(std::filesystem::path(models_dir) /
                                                               m[key].get<std::string>()))
        throw InputError(fmt::format(
            "--objects default: {} is missing under --models-dir {} (the shared data folder)",
            m[key].get<std::string>(), models_dir));
}

}  // namespace

std::unique_ptr<GlSceneObjects> attach_objects(const ObjectsOptions& o, const Terrain& terrain,
                                               Scene* scene, const std::string& mode) {
  if (o.scene.empty()) return nullptr;
  if (!scene)
    throw InputError(fmt::format("--objects {}: --mode {} does not draw objects (GL modes only)",
                                 o.scene, mode));
  const bool builtin = o.scene == "default";
  if (builtin) check_builtin_models(o.models_dir);
  const ObjectLayout objects = builtin ? default_object_layout(o.models_dir, terrain.heights)
                                       : load_object_layout(o.scene, terrain.heights);
  for (const LayoutModel& m : objects.models)
    if (!std::filesystem::is_regular_file(m.file))
      throw InputError(fmt::format("--objects {}: model file {} is missing", o.scene, m.file));
  auto set = std::make_unique<GlSceneObjects>(objects, LodOptions{}, objects_cache_dir(o.cache));
  print_cache_summary(set->cache_stats());
  scene->set_objects(set.get());
  return set;
}

}  // namespace terrasprite
