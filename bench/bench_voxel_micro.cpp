// SPDX-License-Identifier: MIT
// Micro-benchmarks of the voxel ray caster's hot loops: one vertical plane of
// rays (coherent, one level vs multires) and a whole small frame per variant.
#include <benchmark/benchmark.h>

#include <vector>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "voxel/column_march.h"

namespace {
using namespace terrasprite;

const Terrain& terrain() {
  static const Terrain t = [] {
    TerrainOptions o;
    o.synthetic_size = 1025;
    o.erosion_passes = 0;
    return load_terrain(o);
  }();
  return t;
}
const VoxelTerrain& voxels() {
  static const VoxelTerrain v(terrain());
  return v;
}

void BM_ColumnMarch(benchmark::State& state) {
  const bool multires = state.range(0) != 0;
  const Heightfield& h = terrain().heights;
  const double eye[3] = {0.0, -0.6 * h.extent(), h.max_height() + 500.0};
  MarchSettings s;
  s.multires = multires;
  s.pixel_angle = 60.0 * 3.14159265358979323846 / 180.0 / 1080.0;
  ColumnMarcher marcher(voxels(), eye, s);
  std::vector<double> slopes(1080);
  for (int i = 0; i < 1080; ++i) slopes[i] = -0.6 + 0.6 * i / 1080.0;
  std::vector<MarchHit> hits(slopes.size());
  for (auto _ : state) {
    marcher.march(0.1, 0.995, slopes, hits);
    benchmark::DoNotOptimize(hits.data());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(slopes.size()));
}
BENCHMARK(BM_ColumnMarch)->Arg(0)->Arg(1);

void BM_Frame(benchmark::State& state) {
  const int w = 480, h = 270;
  VoxelOptions o;
  o.variant = static_cast<VoxelVariant>(state.range(0));
  o.threads = 1;
  VoxelRenderer r(voxels(), w, h, o);
  const Camera c = paper_path(terrain().heights, 460, double(w) / h)[200];
  for (auto _ : state) benchmark::DoNotOptimize(r.render(c).color.rgba.data());
  state.SetItemsProcessed(state.iterations() * w * h);
}
BENCHMARK(BM_Frame)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
