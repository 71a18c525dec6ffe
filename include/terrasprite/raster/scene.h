// SPDX-License-Identifier: MIT
// What the renderers draw: the terrain with its GPU resources, and the
// objects standing on it (SceneObjects: drawn each frame over the terrain).
#pragma once
#include <memory>

#include "terrasprite/camera/camera.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

/// Objects standing on the terrain (objects/gl_scene_objects.h and
/// hybrid/hybrid_objects.h implement it). The full, LOD and LOD-sprite renderers draw them after the terrain, every frame, into
/// their bound target (reversed-Z float depth, GL_GREATER), depth-tested
/// against what the terrain wrote. Never part of a LOD-sprite keyframe.
class SceneObjects {
 public:
  virtual ~SceneObjects() = default;
  /// Draws every object for `camera`; returns the triangles submitted.
  virtual long long draw(const Camera& camera) = 0;
};

/// How the terrain shader lights the drape (Scene::set_shading).
enum class TerrainShading {
  kPlain,  ///< the drape, with the renderer's optional sun lighting (Lambert)
  /// Soft sun shadows marched through the height field, horizon-based
  /// ambient occlusion and aerial-perspective haze, on every fragment: the
  /// expensive shading a full-resolution renderer pays every frame and
  /// LOD-sprite only on keyframes and drape-textured quads (always lit: the
  /// renderers' `lighting` flag is ignored). About 56 height fetches per fragment.
  kRich,
};

class TerrainGpu;  // the library's GPU side of the terrain (src/scene/terrain_gpu.h)

/// A scene on the GPU. Holds the terrain's drape texture (mipmapped,
/// trilinear) and its grid meshes, one per level, uploaded on first use or by
/// prepare(); grids above 4097 x 4097 samples are drawn in tiles. Needs a
/// current GL context for its whole life (create and destroy it on the thread
/// whose context is current) and keeps a reference to `terrain`, which must
/// outlive it. Renderers keep a reference to their Scene: it must outlive them.
/// Throws InputError when the texture exceeds GL_MAX_TEXTURE_SIZE, and (from
/// prepare) when a mesh would need more than 4 GiB of buffers.
class Scene {
 public:
  explicit Scene(const Terrain& terrain);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  const Terrain& terrain() const;
  /// Uploads the grid mesh of `quads` quads per side (0 = full resolution)
  /// now, so that no timed frame pays for it; returns its triangle count.
  long long prepare(int quads);

  /// Objects to draw over the terrain (not owned; nullptr = none). They must
  /// outlive every draw of a renderer of this scene.
  void set_objects(SceneObjects* objects) { objects_ = objects; }
  bool has_objects() const { return objects_ != nullptr; }
  /// Draws the objects, if any, into the bound target; returns their triangles.
  long long draw_objects(const Camera& camera) { return objects_ ? objects_->draw(camera) : 0; }

  /// The GPU resources, for the library's renderers; the type is internal.
  TerrainGpu& terrain_gpu() { return *terrain_gpu_; }
  /// Terrain shading of every later draw by every renderer of this scene
  /// (default kPlain). kRich uploads the heights as a texture on first use and
  /// throws InputError when they exceed GL_MAX_TEXTURE_SIZE per side.
  void set_shading(TerrainShading shading);
  TerrainShading shading() const;

 private:
  const Terrain& terrain_;
  std::unique_ptr<TerrainGpu> terrain_gpu_;
  SceneObjects* objects_ = nullptr;
};

}  // namespace terrasprite
