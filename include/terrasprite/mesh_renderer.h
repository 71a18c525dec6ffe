// SPDX-License-Identifier: MIT
// GL rasterisation of the terrain: the full-resolution reference renderer and
// plain quadtree LOD, one code path for both.
#pragma once
#include <memory>
#include <string>

#include "terrasprite/renderer.h"
#include "terrasprite/terrain.h"

namespace terrasprite {

/// GPU-resident terrain: the drape texture (mipmapped, trilinear, anisotropic)
/// and grid meshes built on first use (grids above 4097 x 4097 samples in
/// tiles, one draw call each). Needs a current GlContext for its whole life;
/// keeps a reference to `terrain`, which must outlive it. Throws InputError
/// when the texture exceeds GL_MAX_TEXTURE_SIZE, or (from MeshRenderer) when a
/// mesh would need more than 4 GiB of buffers.
class GlTerrain {
 public:
  explicit GlTerrain(const Terrain& terrain);
  ~GlTerrain();
  GlTerrain(const GlTerrain&) = delete;
  GlTerrain& operator=(const GlTerrain&) = delete;
  const Terrain& terrain() const;

  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

struct RasterOptions {
  bool lighting =
      false;  ///< simple diffuse sun; off by default (the derived texture carries hillshade)
  bool read_depth = true;  ///< read linear depth back into Frame::depth
};

/// Draws one grid mesh of `scene` with one indexed draw call into a
/// width x height off-screen target. quads = 0 draws the full-resolution grid
/// (class "full"); otherwise the coarse grid of `quads` quads per side
/// (class "lod"). Frame::ms is wall time to glFinish; gpu_ms from a timer query.
class MeshRenderer : public Renderer {
 public:
  MeshRenderer(GlTerrain& scene, int width, int height, int quads = 0, RasterOptions options = {});
  ~MeshRenderer() override;
  Frame render(const Camera& camera) override;
  std::string name() const override;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace terrasprite
