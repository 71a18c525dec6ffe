// SPDX-License-Identifier: MIT
// A scene's objects standing on the terrain for the commands that draw a
// flythrough (render, bench render): loaded from the built-in scene or a
// scene file, uploaded, and attached to the terrain Scene, whose GL
// renderers then draw them every frame (Scene::set_objects).
#pragma once
#include <memory>
#include <string>

#include "terrasprite/objects/gl_scene_objects.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

/// Which objects stand on the terrain (`--objects`, `--models-dir`, `--objects-cache`).
struct ObjectsOptions {
  std::string scene;  ///< "" none, "default" the built-in 400-instance scene, else a scene file
  std::string models_dir = "../shared/data";
  /// Representation cache folder: "" the default (default_cache_dir()), "off" none.
  std::string cache;
};

/// The folder for GlSceneObjects's cache_dir: "" (no cache) for "off",
/// default_cache_dir() for "", else `option` itself.
std::string objects_cache_dir(const std::string& option);

/// One line on stdout: what the representation cache read and built
/// (nothing when it neither read nor built anything).
void print_cache_summary(const RepresentationCacheStats& s);

/// Loads the scene's objects onto `scene` (GL context current), prints
/// print_cache_summary's line, and returns them (null when none were asked
/// for); they must outlive the drawing. Throws InputError, one line, when a
/// model file is missing (naming it and --models-dir), the scene file is
/// bad, or `scene` is null (a CPU renderer, `mode` naming it).
std::unique_ptr<GlSceneObjects> attach_objects(const ObjectsOptions& o, const Terrain& terrain,
                                               Scene* scene, const std::string& mode);

}  // namespace terrasprite
