// SPDX-License-Identifier: MIT
#include "terrasprite/objects/gl_scene_objects.h"

#include <cassert>
#include <filesystem>

#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/representation_cache.h"

namespace terrasprite {

struct GlSceneObjects::Impl {
  std::vector<LayoutModel> layout_models;
  std::vector<std::unique_ptr<GlModel>> models;
  std::vector<std::vector<ObjectInstance>> instances;
  LodOptions lod;
};

GlSceneObjects::GlSceneObjects(const ObjectLayout& scene, const LodOptions& lod,
                               const std::string& cache_dir)
    : impl_(std::make_unique<Impl>()) {
  impl_->layout_models = scene.models;
  impl_->lod = lod;
  impl_->instances.resize(scene.models.size());
  for (const PlacedInstance& p : scene.instances) impl_->instances[p.model].push_back(p.instance);
  for (const LayoutModel& m : scene.models) {
    const Model model = load_model(m.file, m.options);
    const RepresentationCache cache =
        cache_dir.empty() ? RepresentationCache{}
                          : RepresentationCache(cache_dir, model_source_key(model, m.options),
                                                std::filesystem::path(m.file).stem().string());
    std::vector<LodLevel> chain = cached_lod_chain(model, lod, cache);
    impl_->models.push_back(std::make_unique<GlModel>(model, std::move(chain), cache));
  }
}

const LodOptions& GlSceneObjects::lod() const {
  return impl_->lod;
}

RepresentationCacheStats GlSceneObjects::cache_stats() const {
  RepresentationCacheStats sum;
  for (const auto& m : impl_->models) {
    const RepresentationCacheStats& s = m->cache().stats();
    sum.hits += s.hits;
    sum.misses += s.misses;
    sum.rejected += s.rejected;
    sum.read_ms += s.read_ms;
    sum.build_ms += s.build_ms;
  }
  return sum;
}

GlSceneObjects::~GlSceneObjects() = default;

std::size_t GlSceneObjects::model_count() const {
  return impl_->models.size();
}
const LayoutModel& GlSceneObjects::layout_model(std::size_t i) const {
  return impl_->layout_models[i];
}
GlModel& GlSceneObjects::model(std::size_t i) {
  return *impl_->models[i];
}
std::span<const ObjectInstance> GlSceneObjects::instances(std::size_t i) const {
  return impl_->instances[i];
}

std::size_t GlSceneObjects::instance_count() const {
  std::size_t n = 0;
  for (const auto& v : impl_->instances) n += v.size();
  return n;
}

long long GlSceneObjects::full_triangles() const {
  long long n = 0;
  for (std::size_t i = 0; i < impl_->models.size(); ++i)
    n += (long long)impl_->models[i]->model().triangles() * (long long)impl_->instances[i].size();
  return n;
}

long long GlSceneObjects::draw_with(const Camera& camera,
                                    std::span<const Representation> per_model) {
  assert(per_model.empty() || per_model.size() == impl_->models.size());
  long long triangles = 0;
  for (std::size_t i = 0; i < impl_->models.size(); ++i) {
    const Representation rep = per_model.empty() ? Representation{} : per_model[i];
    impl_->models[i]->draw(rep, impl_->instances[i], camera);
    triangles += impl_->models[i]->triangles(rep) * (long long)impl_->instances[i].size();
  }
  return triangles;
}

}  // namespace terrasprite
