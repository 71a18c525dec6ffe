// SPDX-License-Identifier: MIT
// `--objects default|FILE` for the commands that draw a flythrough (render,
// bench render): a scene's objects standing on the terrain, drawn by the
// GL renderers every frame (Scene::set_objects).
#pragma once
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "terrasprite/objects/object_set.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite::cli {

struct ObjectsOptions {
  std::string scene;  ///< "" none, "default" the built-in 400-instance scene, else a scene file
  std::string models_dir = "../shared/data";
  /// Representation cache folder: "" the default (default_cache_dir()), "off" none.
  std::string cache;
};

/// The folder for ObjectSet: "" (no cache) for "off", default_cache_dir() for "".
std::string objects_cache_dir(const std::string& option);

/// One line on stdout: what the representation cache read and built.
void print_cache_summary(const ObjectSet& set);

void add_objects_options(CLI::App& cmd, ObjectsOptions& o);

/// Loads the scene's objects onto `scene` (GL context current) and returns
/// them (null when none were asked for); they must outlive the drawing.
/// Throws InputError, one line, when a model file is missing (naming it and
/// --models-dir), the scene file is bad, or `scene` is null (a CPU renderer).
std::unique_ptr<ObjectSet> attach_objects(const ObjectsOptions& o, const Terrain& terrain,
                                          Scene* scene, const std::string& mode);

}  // namespace terrasprite::cli
