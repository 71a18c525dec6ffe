// SPDX-License-Identifier: MIT
#include "scene_objects.h"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"
#include "terrasprite/objects/object_scene.h"
#include "terrasprite/objects/representation_cache.h"

namespace terrasprite::cli {

void add_objects_options(CLI::App& cmd, ObjectsOptions& o) {
  cmd.add_option("--objects", o.scene,
                 "objects on the terrain: 'default' (400 instances of 8 models from "
                 "--models-dir) or a scene file (JSON); GL modes only");
  cmd.add_option("--models-dir", o.models_dir, "where the default scene's models are")
      ->capture_default_str();
  cmd.add_option("--objects-cache", o.cache,
                 "where the objects' LOD chains and impostors are cached, or 'off' "
                 "(default: ~/.cache/terrasprite/objects)");
}

std::string objects_cache_dir(const std::string& option) {
  if (option == "off") return {};
  return option.empty() ? default_cache_dir() : option;
}

void print_cache_summary(const ObjectSet& set) {
  const RepresentationCacheStats s = set.cache_stats();
  if (s.hits + s.misses + s.rejected == 0) return;
  fmt::print(
      "objects: {} representations read from the cache in {:.0f} ms, {} built in {:.0f} ms{}\n",
      s.hits, s.read_ms, s.misses, s.build_ms,
      s.rejected ? fmt::format(" ({} unreadable entries rebuilt)", s.rejected) : "");
}

std::unique_ptr<ObjectSet> attach_objects(const ObjectsOptions& o, const Terrain& terrain,
                                          Scene* scene, const std::string& mode) {
  if (o.scene.empty()) return nullptr;
  if (!scene)
    throw InputError(fmt::format("--objects {}: --mode {} does not draw objects (GL modes only)",
                                 o.scene, mode));
  const bool builtin = o.scene == "default";
  // Before placing anything: a missing data folder is the likely mistake.
  const nlohmann::json builtin_models =
      builtin ? nlohmann::json::parse(default_scene_json()).at("models") : nlohmann::json::array();
  for (const auto& m : builtin_models)
    for (const char* key : {"file", "texture"})
      if (m.contains(key) && !std::filesystem::is_regular_file(std::filesystem::path(o.models_dir) /
                                                               m[key].get<std::string>()))
        throw InputError(fmt::format(
            "--objects default: {} is missing under --models-dir {} (the shared data folder)",
            m[key].get<std::string>(), o.models_dir));
  const ObjectScene objects = builtin ? default_object_scene(o.models_dir, terrain.heights)
                                      : load_object_scene(o.scene, terrain.heights);
  for (const SceneModel& m : objects.models)
    if (!std::filesystem::is_regular_file(m.file))
      throw InputError(fmt::format("--objects {}: model file {} is missing", o.scene, m.file));
  auto set = std::make_unique<ObjectSet>(objects, LodOptions{}, objects_cache_dir(o.cache));
  print_cache_summary(*set);
  scene->set_objects(set.get());
  return set;
}

}  // namespace terrasprite::cli
