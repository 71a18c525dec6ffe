// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/hybrid_renderer.h"

#include "terrasprite/raster/mesh_renderer.h"

namespace terrasprite {

RasterOptions hybrid_terrain_raster(int samples) {
  // Never llvmpipe's anisotropic path: it stalls for seconds at grazing
  // angles, and a walkthrough is all grazing angles. Trilinear, not the hand
  // filter: the terrain is the same in every scenario, and the time the
  // hand filter would take goes to the objects. Back faces culled: the
  // walkthrough stands on the drawn grid, so they are never seen (bar a
  // pixel on a ridge's silhouette), and their setup is skipped
  // (docs/results/2026-12-01-hybrid-terrain-drape.md).
  return {.drape_filter = DrapeFilter::kTrilinear, .cull_back_faces = true, .samples = samples};
}

HybridRenderer::HybridRenderer(Scene& scene, HybridObjects* objects, std::string name, int width,
                               int height, int terrain_quads, int samples)
    : scene_(scene), objects_(objects), name_(std::move(name)) {
  terrain_ = std::make_unique<MeshRenderer>(scene, width, height, terrain_quads,
                                            hybrid_terrain_raster(samples));
}

HybridRenderer::~HybridRenderer() = default;

Frame HybridRenderer::draw(const Camera& camera) {
  scene_.set_objects(objects_);
  Frame f = terrain_->draw(camera);
  scene_.set_objects(nullptr);
  if (objects_) objects_->feedback(f.ms);
  f.cls = FrameClass::kObjects;
  return f;
}

void HybridRenderer::read_back(Frame& frame, ReadBack what) {
  terrain_->read_back(frame, what);
}

}  // namespace terrasprite
