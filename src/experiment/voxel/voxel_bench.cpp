// SPDX-License-Identifier: MIT
// The voxel study (terrasprite/experiment/voxel.h): the interleaved path run,
// then the pitch and terrain-size sweeps, each a stage below.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <thread>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/experiment/voxel.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite {
namespace {

constexpr std::size_t kVariants = kVoxelBenchVariants.size();
constexpr std::size_t kDefault = kVariants - 1;  // multires

// The renderers of the path run: every variant at every thread count, and
// the supersampled reference at the largest.
struct Rig {
  const VoxelBenchOptions& o;
  std::unique_ptr<VoxelTerrain> voxels;
  std::vector<std::vector<std::unique_ptr<VoxelRenderer>>> renderers;  // [variant][thread index]
  std::unique_ptr<VoxelReference> reference;
  int tmax = 0;
  std::size_t ti_max = 0;  // index of tmax in o.threads

  std::string run_name(std::size_t v, std::size_t t) const {
    return fmt::format("{}@{}", to_string(kVoxelBenchVariants[v]), o.threads[t]);
  }
};

Rig build_rig(const Terrain& terrain, const VoxelBenchOptions& o) {
  Rig rig{o};
  rig.tmax = *std::max_element(o.threads.begin(), o.threads.end());
  rig.ti_max = std::size_t(std::find(o.threads.begin(), o.threads.end(), rig.tmax) -
                           o.threads.begin());
  rig.voxels = std::make_unique<VoxelTerrain>(terrain);
  rig.renderers.resize(kVariants);
  for (std::size_t v = 0; v < kVariants; ++v)
    for (int t : o.threads) {
      VoxelOptions vo;
      vo.variant = kVoxelBenchVariants[v];
      vo.threads = t;
      vo.pixel_voxel_ratio = o.pixel_voxel_ratio;
      rig.renderers[v].push_back(
          std::make_unique<VoxelRenderer>(*rig.voxels, o.width, o.height, vo));
    }
  ReferenceOptions ro;
  ro.supersample = o.supersample;
  ro.threads = rig.tmax;
  rig.reference = std::make_unique<VoxelReference>(*rig.voxels, o.width, o.height, ro);
  return rig;
}

// SSIM, PSNR and FLIP against the reference, and SSIM of the terrain pixels
// alone: the paper path's frames are mostly sky.
QualityScore score(const Frame& ref, const Frame& f) {
  QualityScore q;
  q.ssim = quality::ssim(ref.color.view(), f.color.view()).ssim;
  std::vector<std::uint8_t> terrain_mask(ref.depth.size());
  for (std::size_t k = 0; k < terrain_mask.size(); ++k)
    terrain_mask[k] = std::isfinite(ref.depth[k]);
  q.figures["ssim_terrain"] =
      quality::ssim(ref.color.view(), f.color.view(), {}, terrain_mask).ssim;
  q.psnr = std::min(quality::psnr(ref.color.view(), f.color.view()).rgb, kPsnrCapDb);
  q.flip = quality::flip(ref.color.view(), f.color.view()).mean;
  return q;
}

// Interleaved: every variant at every thread count on each frame (naive,
// seconds a frame at 1080p, on scored frames only); the reference and the
// scores on scored frames, at the largest thread count.
ExperimentResult run_path(Rig& rig, const std::vector<Camera>& path) {
  const VoxelBenchOptions& o = rig.o;
  Experiment experiment;
  experiment.set_reference({.renderer = rig.reference.get(),
                            .name = "reference",
                            .warmup_draws = 0,
                            .read = ReadBack::kColorDepth});
  for (std::size_t v = 0; v < kVariants; ++v) {
    const bool naive = kVoxelBenchVariants[v] == VoxelVariant::kNaive;
    for (std::size_t t = 0; t < o.threads.size(); ++t)
      experiment.add({.renderer = rig.renderers[v][t].get(),
                      .name = rig.run_name(v, t),
                      .score = t == rig.ti_max,
                      .every = naive ? o.score_every : 1,
                      // warm-up: thread pools, first touch (naive needs none)
                      .warmup_draws = naive ? 0 : 1});
  }
  ExperimentOptions eo;
  eo.score_every = o.score_every;
  eo.scorer = score;
  const std::string saved = rig.run_name(kDefault, rig.ti_max);
  eo.on_frame = [&](int i, const std::string& name, const Frame& f) {
    if (!o.on_image) return;
    if (name == "reference") o.on_image(VoxelBenchImage::kReference, i, f.color);
    if (name == saved && i % o.score_every == 0) o.on_image(VoxelBenchImage::kMultires, i, f.color);
  };
  eo.progress = o.progress;
  PathSource cameras(path);
  return experiment.run(cameras, eo);
}

// Each variant's figures at the largest thread count (ms[t]: its frame times
// at each thread count; naive: scored frames only).
VoxelVariantResult variant_result(const Rig& rig, const ExperimentResult& r, std::size_t v,
                                  double naive_scored_median) {
  const VoxelBenchOptions& o = rig.o;
  std::vector<std::vector<double>> ms(o.threads.size());
  std::vector<double> scored_ms;
  for (std::size_t t = 0; t < o.threads.size(); ++t)
    for (const FrameResult& f : r.run(rig.run_name(v, t)).frames) {
      ms[t].push_back(f.ms);
      if (t == rig.ti_max && f.quality) scored_ms.push_back(f.ms);
    }
  VoxelVariantResult out;
  out.variant = kVoxelBenchVariants[v];
  out.threads = rig.tmax;
  out.frame_ms = ms[rig.ti_max];
  out.median_ms = median(out.frame_ms);
  out.p95_ms = percentile(out.frame_ms, 95);
  out.ns_per_pixel = out.median_ms * 1e6 / (double(o.width) * o.height);
  out.speedup_vs_naive = naive_scored_median / std::max(median(scored_ms), 1e-9);
  const auto one = std::find(o.threads.begin(), o.threads.end(), 1),
             two = std::find(o.threads.begin(), o.threads.end(), 2);
  const bool both = one != o.threads.end() && two != o.threads.end();
  out.scaling_2v1 = both ? median(ms[std::size_t(one - o.threads.begin())]) /
                               std::max(median(ms[std::size_t(two - o.threads.begin())]), 1e-9)
                         : NAN;
  for (std::size_t t = 0; t < o.threads.size(); ++t)
    out.median_ms_by_threads.emplace_back(o.threads[t], median(ms[t]));
  const RendererRun& run = r.run(rig.run_name(v, rig.ti_max));
  out.ssim = run.quality("ssim");
  out.ssim_terrain = run.quality("ssim_terrain");
  out.psnr = run.quality("psnr");
  out.flip = run.quality("flip");
  return out;
}

std::vector<VoxelFrameRow> frame_rows(const Rig& rig, const ExperimentResult& r) {
  std::vector<VoxelFrameRow> rows(std::size_t(r.frames));
  for (int i = 0; i < r.frames; ++i) rows[std::size_t(i)].frame = i;
  for (std::size_t v = 0; v < kVariants; ++v)
    for (const FrameResult& f : r.run(rig.run_name(v, rig.ti_max)).frames) {
      rows[std::size_t(f.frame)].ms[v] = f.ms;
      if (f.quality) rows[std::size_t(f.frame)].ssim[v] = f.quality->ssim;
    }
  for (const FrameResult& f : r.run("reference").frames)
    rows[std::size_t(f.frame)].reference_ms = f.ms;
  return rows;
}

// A static view over the terrain for the pitch sweep: south of the centre,
// high enough to see the whole terrain at -90 and a horizon at -10.
Camera pitch_camera(const Heightfield& h, double pitch_deg, double aspect) {
  const double E = h.extent();
  Camera c;
  c.position = {0.0, -0.25 * E, double(h.max_height()) + 0.15 * E};
  c.yaw_deg = 0;
  c.pitch_deg = pitch_deg;
  c.fov_y_deg = 60;
  c.aspect = aspect;
  fit_clip_planes(c, h);
  return c;
}

// Static pitch sweep (paper Table 1): the default variant at each thread
// count, five timed draws of each static view, thread counts interleaved.
std::vector<VoxelPitchRow> pitch_sweep(Rig& rig, const Heightfield& h) {
  const VoxelBenchOptions& o = rig.o;
  std::vector<VoxelPitchRow> rows;
  for (double p : o.pitches) {
    Experiment table;
    for (std::size_t t = 0; t < o.threads.size(); ++t)
      table.add({.renderer = rig.renderers[kDefault][t].get(), .name = rig.run_name(kDefault, t)});
    PathSource view(std::vector<Camera>(5, pitch_camera(h, p, double(o.width) / o.height)));
    ExperimentOptions to;
    to.warmup_draws = 1;
    const ExperimentResult r = table.run(view, to);
    for (std::size_t t = 0; t < o.threads.size(); ++t) {
      const double m = r.run(rig.run_name(kDefault, t)).ms().median;
      rows.push_back({p, o.threads[t], m, 1000.0 / std::max(m, 1e-9)});
    }
  }
  return rows;
}

// One terrain of the size sweep: its pyramids, renderer and path.
struct SweepEntry {
  int samples;
  std::unique_ptr<VoxelTerrain> voxels;
  std::unique_ptr<VoxelRenderer> renderer;
  std::vector<Camera> path;
};

SweepEntry sweep_entry(const VoxelBenchOptions& o, int samples, int threads) {
  TerrainOptions to;
  to.synthetic_size = samples;
  to.erosion_passes = 0;
  to.seed = o.sweep_seed;
  SweepEntry e;
  e.samples = samples;
  {
    Terrain big = load_terrain(to);  // dropped once the pyramids are built
    e.voxels = std::make_unique<VoxelTerrain>(big);
    e.path = make_path(o.path, big.heights, std::max(1, std::min(o.sweep_frames, o.frames)),
                       double(o.width) / o.height);
  }
  VoxelOptions vo;
  vo.threads = threads;
  vo.pixel_voxel_ratio = o.pixel_voxel_ratio;
  e.renderer = std::make_unique<VoxelRenderer>(*e.voxels, o.width, o.height, vo);
  return e;
}

// Terrain size sweep: the same kind of path over synthetic terrains (no
// erosion), each planned over its own terrain, the sizes interleaved frame
// by frame so machine noise hits them alike.
std::vector<VoxelSizeRow> size_sweep(const VoxelBenchOptions& o, int threads) {
  std::vector<SweepEntry> entries;
  for (int n : o.terrain_sizes) entries.push_back(sweep_entry(o, n, threads));
  std::vector<VoxelSizeRow> rows;
  if (entries.empty()) return rows;
  Experiment by_size;
  for (const SweepEntry& e : entries)
    by_size.add({.renderer = e.renderer.get(),
                 .name = std::to_string(e.samples),
                 .camera_for = [&e](int i, const Camera&) { return e.path[std::size_t(i)]; }});
  PathSource frames(entries[0].path);  // the count; each size flies its own path
  const ExperimentResult r = by_size.run(frames, {});
  for (const SweepEntry& e : entries) {
    const Summary ms = r.run(std::to_string(e.samples)).ms();
    rows.push_back({e.samples, int(e.path.size()), ms.median, ms.p95});
  }
  return rows;
}

}  // namespace

VoxelBenchResult run_voxel_bench(const Terrain& terrain, const VoxelBenchOptions& o) {
  const std::vector<Camera> path =
      make_path(o.path, terrain.heights, o.frames, double(o.width) / o.height);
  Rig rig = build_rig(terrain, o);
  const ExperimentResult r = run_path(rig, path);

  VoxelBenchResult res;
  res.hardware_threads = int(std::thread::hardware_concurrency());
  res.terrain = terrain_info(terrain);
  res.width = o.width;
  res.height = o.height;
  res.path = o.path;
  res.frames = int(path.size());
  res.score_every = o.score_every;
  res.pixel_voxel_ratio = o.pixel_voxel_ratio;
  res.supersample = o.supersample;
  res.threads = o.threads;
  const RendererRun& ref = r.run("reference");
  res.scored_frames = int(ref.frames.size());
  std::vector<double> ref_ms;
  for (const FrameResult& f : ref.frames) ref_ms.push_back(f.ms);
  res.reference_median_ms = median(ref_ms);
  std::vector<double> naive_scored;
  for (const FrameResult& f : r.run(rig.run_name(0, rig.ti_max)).frames)
    if (f.quality) naive_scored.push_back(f.ms);
  for (std::size_t v = 0; v < kVariants; ++v)
    res.variants.push_back(variant_result(rig, r, v, median(naive_scored)));
  res.scaling_2v1 = res.variants[kDefault].scaling_2v1;
  res.per_frame = frame_rows(rig, r);
  res.pitch_table = pitch_sweep(rig, terrain.heights);
  res.terrain_size_sweep = size_sweep(o, rig.tmax);
  return res;
}

}  // namespace terrasprite
