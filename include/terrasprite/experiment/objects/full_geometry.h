// SPDX-License-Identifier: MIT
// `objects scene`: a scene's objects on the terrain at full geometry, all in
// view: the frame time a representation budget has to beat.
#pragma once
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/common/image.h"
#include "terrasprite/objects/object_layout.h"
#include "terrasprite/objects/representation_cache.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

struct FullGeometryOptions {
  std::string scene;  ///< scene file (JSON); empty: the built-in default scene
  std::string models_dir = "../shared/data";  ///< where the default scene's models are
  int width = 1280, height = 720;             ///< image size, px
  int frames = 5;                             ///< timed frames, >= 1 (one more warms up)
  /// Representation cache folder (objects_cache_dir()); empty: no cache.
  std::string cache_dir;
};

/// One model of the scene as loaded.
struct FullGeometryModel {
  std::string name, file;
  std::size_t triangles = 0;  ///< of the full model
  std::size_t instances = 0;
  std::size_t lod_levels = 0;  ///< levels of its LOD chain, the full model included
};

struct FullGeometryResult {
  std::string gl_renderer;  ///< GL_RENDERER
  int width = 0, height = 0;
  std::size_t instances = 0;
  double load_ms = 0;  ///< loading and uploading the objects (cache reads or builds included)
  RepresentationCacheStats representation_cache;
  long long full_triangles = 0;     ///< every instance at full geometry
  long long terrain_triangles = 0;  ///< the terrain alone, one frame
  long long frame_triangles = 0;    ///< terrain and objects, one frame
  int frames = 0;
  /// Per timed frame, ms: the full-resolution renderer with the objects, and
  /// without them (interleaved frame by frame, the warm-up frame left out).
  std::vector<double> frame_ms, terrain_ms;
  double median_ms = 0, terrain_median_ms = 0;  ///< common/stats median of the above
  std::vector<FullGeometryModel> models;
  Image frame;          ///< the last frame with the objects, RGBA8
  Camera camera;        ///< the view timed and drawn
  ObjectLayout placed;  ///< every instance where it was drawn (scene-file form: object_layout_json)
};

/// Loads the scene onto `terrain` (the default scene when options.scene is
/// empty), frames every instance from the south, 35 degrees down, and times
/// the full-resolution renderer with and without the objects. Creates its
/// own GlContext. Throws InputError for a bad scene file or a model that
/// cannot be loaded.
FullGeometryResult run_full_geometry(const FullGeometryOptions& options, const Terrain& terrain);

}  // namespace terrasprite
