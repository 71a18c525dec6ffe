// SPDX-License-Identifier: MIT
// The objects of a layout on the GPU: every model loaded, its LOD chain
// built and uploaded, its instances grouped for instanced drawing.
// Names of what stands on the terrain: a Scene is the terrain on the GPU;
// ObjectLayout says which models stand where (loaded from a scene file);
// SceneObjects is what a Scene draws over its terrain, GlSceneObjects (every
// instance uploaded) and HybridObjects (representations under a budget)
// its implementations.
#pragma once
#include <memory>
#include <span>
#include <vector>

#include "terrasprite/objects/object_layout.h"
#include "terrasprite/objects/object_renderer.h"
#include "terrasprite/raster/scene.h"

namespace terrasprite {

/// Needs a current GlContext for its whole life. Throws InputError (from the
/// loaders) naming a model that cannot be loaded. As SceneObjects
/// (Scene::set_objects) it draws every instance at full geometry.
/// `cache_dir`: where each model's LOD chain and impostors are cached
/// (RepresentationCache; empty: no cache, everything built here).
class GlSceneObjects : public SceneObjects {
 public:
  explicit GlSceneObjects(const ObjectLayout& layout, const LodOptions& lod = {},
                          const std::string& cache_dir = {});
  ~GlSceneObjects() override;
  GlSceneObjects(const GlSceneObjects&) = delete;
  GlSceneObjects& operator=(const GlSceneObjects&) = delete;

  std::size_t model_count() const;
  const LayoutModel& layout_model(std::size_t i) const;
  /// The options the models' LOD chains were built with.
  const LodOptions& lod() const;
  GlModel& model(std::size_t i);
  std::span<const ObjectInstance> instances(std::size_t i) const;
  std::size_t instance_count() const;
  /// Triangles of every instance at full geometry.
  long long full_triangles() const;
  /// The representation caches' counters, summed over the models.
  RepresentationCacheStats cache_stats() const;

  /// Draws every instance into the bound target (RenderTarget conventions):
  /// model i with `per_model[i]` (one per model), or its full mesh when
  /// `per_model` is empty. One instanced draw per model part (or impostor).
  /// Returns the triangles submitted.
  long long draw_with(const Camera& camera, std::span<const Representation> per_model);
  long long draw(const Camera& camera) override { return draw_with(camera, {}); }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace terrasprite
