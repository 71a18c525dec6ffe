// SPDX-License-Identifier: MIT
// The objects' draw calls at a walkthrough view (the default scene at
// checkpoint B, each model's instances spread over four representations):
// group by group, each with its own upload of the instance buffer, against
// one upload per model and base-instance offsets. Under llvmpipe a write
// to a buffer that a queued draw reads drains the pipeline first; measured
// on the 2-core llvmpipe machine, mostly quiet: 28.4 vs 27.8 ms median of
// 20 interleaved repetitions (2%, inside the 5% spread).
// TS_MODELS_DIR: the default scene's models (default ../shared/data).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <vector>

#include "gl/render_target.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/hybrid/walkthrough_path.h"
#include "terrasprite/objects/gl_scene_objects.h"
#include "terrasprite/objects/object_layout.h"
#include "terrasprite/objects/representation_cache.h"
#include "terrasprite/terrain/terrain.h"

namespace {
using namespace terrasprite;

struct Fixture {
  GlContext gl;
  Terrain terrain = load_terrain(TerrainOptions{});
  std::unique_ptr<GlSceneObjects> set;
  std::vector<ObjectInstance> instances;            ///< per model, grouped
  std::vector<std::vector<GlModel::Group>> groups;  ///< per model
  gl::RenderTarget target{320, 180};
  Camera camera;

  Fixture() {
    const char* dir = std::getenv("TS_MODELS_DIR");
    set = std::make_unique<GlSceneObjects>(
        default_object_layout(dir ? dir : "../shared/data", terrain.heights), LodOptions{},
        default_cache_dir());
    camera = sample_path(walkthrough_path(terrain.heights), terrain.heights, 160, 320.0 / 180)[40];
    std::size_t total = 0;
    for (std::size_t m = 0; m < set->model_count(); ++m) total += set->instances(m).size();
    instances.reserve(total);  // the groups' spans point into it
    for (std::size_t m = 0; m < set->model_count(); ++m) {
      const int last = int(set->model(m).chain().size()) - 1;
      const Representation reps[4] = {{ObjectKind::kMesh, std::min(1, last)},
                                      {ObjectKind::kMesh, last},
                                      {ObjectKind::kRelief, 0, 64},
                                      {ObjectKind::kOctahedral, 0, 64}};
      for (const Representation& r : reps)
        if (r.kind != ObjectKind::kMesh) set->model(m).prepare(r);
      const auto all = set->instances(m);
      groups.emplace_back();
      for (int g = 0; g < 4; ++g) {
        const std::size_t first = instances.size();
        for (std::size_t i = std::size_t(g); i < all.size(); i += 4) instances.push_back(all[i]);
        groups.back().push_back(
            {reps[g], std::span(instances.data() + first, instances.size() - first)});
      }
    }
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_ObjectGroups(benchmark::State& state) {
  Fixture& f = fixture();
  const bool at_once = state.range(0) != 0;
  for (auto _ : state) {
    f.target.bind_and_clear();
    for (std::size_t m = 0; m < f.groups.size(); ++m) {
      if (at_once)
        f.set->model(m).draw(f.groups[m], f.camera);
      else
        for (const GlModel::Group& g : f.groups[m])
          f.set->model(m).draw(g.rep, g.instances, f.camera);
    }
    glFinish();
  }
  state.SetLabel(at_once ? "one upload per model" : "one upload per group");
}
BENCHMARK(BM_ObjectGroups)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
