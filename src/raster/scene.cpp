// SPDX-License-Identifier: MIT
#include "terrasprite/raster/scene.h"

#include "raster/terrain_gpu.h"

namespace terrasprite {

Scene::Scene(const Terrain& terrain)
    : terrain_(terrain), terrain_gpu_(std::make_unique<TerrainGpu>(terrain)) {}

Scene::~Scene() = default;

const Terrain& Scene::terrain() const {
  return terrain_;
}

void Scene::set_shading(TerrainShading shading) {
  terrain_gpu_->set_shading(shading);
}

TerrainShading Scene::shading() const {
  return terrain_gpu_->shading();
}

long long Scene::prepare(int quads) {
  return terrain_gpu_->mesh(quads).triangles;
}

}  // namespace terrasprite
