// SPDX-License-Identifier: MIT
// Object scenes: which models stand on the terrain, and where. Read from a
// scene file (JSON, schema in the README) or the built-in default scene.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "terrasprite/terrain/heightfield.h"
#include "terrasprite/objects/model.h"
#include "terrasprite/objects/object_renderer.h"

namespace terrasprite {

/// A model of a scene: its file and how to bring it to metres.
struct SceneModel {
  std::string name;
  std::string file;  ///< resolved path
  ModelOptions options;
};

/// One instance of `model` (index into ObjectScene::models).
struct PlacedInstance {
  int model = 0;
  ObjectInstance instance;
  /// Stands on the terrain (its height came from it, not from the file):
  /// ground_instances may move it onto the surface actually drawn.
  bool grounded = true;
};

struct ObjectScene {
  std::vector<SceneModel> models;
  std::vector<PlacedInstance> instances;
};

/// Parses a scene from JSON text. Relative model and texture paths resolve
/// against `base_dir`. Listed instances without a height stand on the
/// terrain (its full-resolution triangles, grid_surface(heights, 0), as the
/// GL renderers draw it); scattered ones are placed at random (seeded,
/// reproducible) in their region, on slopes under the limit, at least the minimum spacing from
/// every instance placed before. Throws InputError naming `name` for bad JSON,
/// unknown keys' values, an unknown model, a region off the terrain, or a
/// scatter that cannot place its count.
ObjectScene parse_object_scene(const std::string& json_text, const std::string& name,
                               const std::string& base_dir, const Heightfield& heights);

/// Reads and parses a scene file (relative paths against its directory).
ObjectScene load_object_scene(const std::string& path, const Heightfield& heights);

/// The default scene: 400 instances of 8 models (the six scans, the Cesium
/// Milk Truck, the Kenney forest patch) scattered over the terrain's centre,
/// at least 1.5 million triangles at full geometry. Model paths resolve
/// against `models_dir` (the shared data folder).
ObjectScene default_object_scene(const std::string& models_dir, const Heightfield& heights);

/// Sets the height of every grounded instance to `ground(x, y)` (metres):
/// the surface the terrain is drawn with, where that is not the heightfield's
/// bilinear one (grid_surface_height for a coarse grid).
void ground_instances(ObjectScene& scene, const std::function<double(double, double)>& ground);

/// The default scene's JSON text (what default_object_scene parses).
const char* default_scene_json();

}  // namespace terrasprite
