// SPDX-License-Identifier: MIT
// One hybrid scenario as a Renderer: the terrain as a fixed coarse mesh with
// a trilinear drape and its back faces culled (the same in every scenario,
// counted in the frame time), then the scenario's objects; the measured frame
// time is fed back to the objects' controller after each draw. Cameras and
// objects belong on that mesh's surface (grid_surface_height,
// keep_above_ground): from under it, the culled terrain shows the sky.
#pragma once
#include <memory>
#include <string>

#include "terrasprite/hybrid/hybrid_objects.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/camera/renderer.h"
#include "terrasprite/raster/scene.h"

namespace terrasprite {

/// How the walkthrough's terrain is rasterised: by every scenario, and by
/// anything that must draw the same views (the quality diagnosis' shots),
/// with `samples` a pixel (RasterOptions::samples).
RasterOptions hybrid_terrain_raster(int samples = 1);

class HybridRenderer : public Renderer {
 public:
  /// `objects` may be null (terrain alone). `scene`, `objects` must outlive
  /// it. Needs a current GL context. Throws InputError for a bad `quads` or
  /// `samples` (a pixel's, as RasterOptions::samples).
  HybridRenderer(Scene& scene, HybridObjects* objects, std::string name, int width, int height,
                 int terrain_quads = 64, int samples = 1);
  ~HybridRenderer() override;
  Frame draw(const Camera& camera) override;
  void read_back(Frame& frame, ReadBack what) override;
  std::string name() const override { return name_; }

 private:
  Scene& scene_;
  HybridObjects* objects_;
  std::string name_;
  std::unique_ptr<Renderer> terrain_;
};

}  // namespace terrasprite
