// SPDX-License-Identifier: MIT
// What the renderers draw: the terrain with its GPU resources, and (as the
// hybrid-object system lands) the object instances standing on it.
#pragma once
#include <memory>

#include "terrasprite/terrain.h"

namespace terrasprite {

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

  /// The GPU resources, for the library's renderers; the type is internal.
  TerrainGpu& terrain_gpu() { return *terrain_gpu_; }

 private:
  const Terrain& terrain_;
  std::unique_ptr<TerrainGpu> terrain_gpu_;
};

}  // namespace terrasprite
