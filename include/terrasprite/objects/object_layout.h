// SPDX-License-Identifier: MIT
// Object layouts: which models stand on the terrain, and where. Read from a
// scene file (JSON, docs/formats.md "Scene files") or the built-in default scene.
// Names of what stands on the terrain: a Scene is the terrain on the GPU;
// ObjectLayout says which models stand where (loaded from a scene file);
// SceneObjects is what a Scene draws over its terrain, GlSceneObjects (every
// instance uploaded) and HybridObjects (representations under a budget)
// its implementations.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "terrasprite/objects/model.h"
#include "terrasprite/objects/object_renderer.h"
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// A model of a layout: its file and how to bring it to metres.
struct LayoutModel {
  std::string name;
  std::string file;  ///< resolved path
  ModelOptions options;
};

/// One instance of `model` (index into ObjectLayout::models).
struct PlacedInstance {
  int model = 0;
  ObjectInstance instance;
  /// Stands on the terrain (its height came from it, not from the file):
  /// ground_instances may move it onto the surface actually drawn.
  bool grounded = true;
};

struct ObjectLayout {
  std::vector<LayoutModel> models;
  std::vector<PlacedInstance> instances;
};

/// Parses a layout from a scene file's JSON text. Relative model and texture paths resolve
/// against `base_dir`. Listed instances without a height stand on the
/// terrain (its full-resolution triangles, grid_surface(heights, 0), as the
/// GL renderers draw it); scattered ones are placed at random (seeded,
/// reproducible) in their region, on slopes under the limit, at least the minimum spacing from
/// every instance placed before (a grid as wide as the spacing: linear in the
/// count). Throws InputError naming `name` and the JSON field for bad JSON, a
/// value of the wrong type or out of its range (docs/formats.md "Scene
/// files": positions near the terrain, scales in [0.001, 1000], counts up to
/// 1,000,000, ...), an unknown model, a region off the terrain, or a scatter
/// that cannot place its count. Headings are reduced into [0, 360).
ObjectLayout parse_object_layout(const std::string& json_text, const std::string& name,
                                 const std::string& base_dir, const Heightfield& heights);

/// Reads a scene file and parses its layout (relative paths against its directory).
ObjectLayout load_object_layout(const std::string& path, const Heightfield& heights);

/// The default layout: 400 instances of 8 models (the six scans, the Cesium
/// Milk Truck, the Kenney forest patch) scattered over the terrain's centre,
/// at least 1.5 million triangles at full geometry. Model paths resolve
/// against `models_dir` (the shared data folder).
ObjectLayout default_object_layout(const std::string& models_dir, const Heightfield& heights);

/// Sets the height of every grounded instance to `ground(x, y)` (metres):
/// the surface the terrain is drawn with, where that is not the heightfield's
/// bilinear one (grid_surface_height for a coarse grid).
void ground_instances(ObjectLayout& layout, const std::function<double(double, double)>& ground);

/// The default layout's scene-file JSON text (what default_object_layout parses).
const char* default_layout_json();

}  // namespace terrasprite
