// SPDX-License-Identifier: MIT
#include "terrasprite/scene.h"

#include "scene/terrain_gpu.h"

namespace terrasprite {

Scene::Scene(const Terrain& terrain)
    : terrain_(terrain), terrain_gpu_(std::make_unique<TerrainGpu>(terrain)) {}

Scene::~Scene() = default;

const Terrain& Scene::terrain() const {
  return terrain_;
}

long long Scene::prepare(int quads) {
  return terrain_gpu_->mesh(quads).triangles;
}

}  // namespace terrasprite
