// SPDX-License-Identifier: MIT
// terrasprite bench voxel: the CPU ray caster's speed and quality. Variants
// (naive, coherent, multires) at each thread count are rendered interleaved
// frame by frame, so machine noise hits them alike; the slow naive variant and
// the supersampled reference run on every --score-every-th frame only, and
// quality is computed outside every timed span.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <thread>

#include "bench_commands.h"
#include "cli_common.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite::cli {
namespace {

struct BenchVoxelOpts {
  TerrainOptions terrain;
  std::string size = "1920x1080";
  std::string path = "paper";
  int frames = 460;
  std::string threads = "1,2";
  std::string pitches = "-10,-30,-60,-90";
  int score_every = 20;
  std::string terrain_sizes = "1025,4097";
  int sweep_frames = 46;
  double ratio = 1.0;
  int supersample = 2;
  std::string json;
  std::string out;
};

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

void write_plot(const OutputDir& out, const std::vector<std::string>& names,
                const std::vector<std::vector<double>>& ms) {
  std::ofstream dat(out.file("frame_times.dat"));
  dat << "# frame";
  for (const auto& n : names) dat << ' ' << n << "_ms";
  dat << '\n';
  for (std::size_t i = 0; i < ms[0].size(); ++i) {
    dat << i;
    for (const auto& m : ms) dat << ' ' << m[i];
    dat << '\n';
  }
  dat.close();
  std::ofstream gp(out.file("frame_times.gp"));
  gp << "set terminal pngcairo size 1000,500\nset output 'frame_times.png'\n"
     << "set xlabel 'frame along the path'\nset ylabel 'ms per frame'\nset key top left\nset grid\n"
     << "plot ";
  for (std::size_t k = 0; k < names.size(); ++k)
    gp << (k ? ", " : "") << "'frame_times.dat' using 1:" << k + 2 << " with lines title '"
       << names[k] << "'";
  gp << '\n';
  gp.close();
  const std::string error = run_gnuplot(out.partial().string(), "frame_times.gp");
  if (!error.empty())
    fmt::print(stderr, "warning: {}; frame_times.dat kept without a plot\n", error);
}

void run(const BenchVoxelOpts& o) {
  auto [w, h] = parse_size(o.size, "--size");
  if (o.frames < 1 || o.frames > 100000)
    throw InputError(fmt::format("--frames {}: must be between 1 and 100000", o.frames));
  if (o.score_every < 1)
    throw InputError(fmt::format("--score-every {}: must be at least 1", o.score_every));
  std::vector<int> threads;
  for (double t : parse_list(o.threads, "--threads")) {
    // TBB runs at most one thread per hardware thread: a larger count would be
    // reported while fewer ran.
    const int most = int(std::max(1u, std::thread::hardware_concurrency()));
    if (t < 1 || t > most || t != std::floor(t))
      throw InputError(fmt::format(
          "--threads {}: counts must be whole, 1..{} (the hardware threads of this machine)",
          o.threads, most));
    threads.push_back(int(t));
  }
  std::vector<double> pitches = parse_list(o.pitches, "--pitches");
  for (double p : pitches)
    if (p < -90 || p > 90)
      throw InputError(fmt::format("--pitches {}: angles must be within -90..90", o.pitches));
  std::vector<int> sizes;
  if (!o.terrain_sizes.empty() && o.terrain_sizes != "none")
    for (double s : parse_list(o.terrain_sizes, "--terrain-sizes")) {
      if (s < 2 || s > 8193 || s != std::floor(s))  // the synthetic terrain's bound
        throw InputError(
            fmt::format("--terrain-sizes {}: sizes must be whole, 2..8193", o.terrain_sizes));
      sizes.push_back(int(s));
    }
  const int tmax = *std::max_element(threads.begin(), threads.end());
  const std::string out_dir = o.out.empty() ? std::string("out/bench_voxel") : o.out;
  check_outputs(out_dir, {o.json});
  Terrain terrain = load_terrain_verbose(o.terrain);
  std::vector<Camera> path = make_path(o.path, terrain.heights, o.frames, double(w) / h);
  OutputDir out(out_dir, output_policy());

  VoxelTerrain vt(terrain);
  const std::vector<VoxelVariant> variants = {VoxelVariant::kNaive, VoxelVariant::kCoherent,
                                              VoxelVariant::kMultires};
  // renderers[v][t]
  std::vector<std::vector<std::unique_ptr<VoxelRenderer>>> renderers(variants.size());
  for (std::size_t v = 0; v < variants.size(); ++v)
    for (int t : threads) {
      VoxelOptions vo;
      vo.variant = variants[v];
      vo.threads = t;
      vo.pixel_voxel_ratio = o.ratio;
      renderers[v].push_back(std::make_unique<VoxelRenderer>(vt, w, h, vo));
    }
  ReferenceOptions ro;
  ro.supersample = o.supersample;
  ro.threads = tmax;
  VoxelReference reference(vt, w, h, ro);
  const std::size_t ti_max =
      std::size_t(std::find(threads.begin(), threads.end(), tmax) - threads.begin());
  auto run_name = [&](std::size_t v, std::size_t t) {
    return fmt::format("{}@{}", to_string(variants[v]), threads[t]);
  };

  // Interleaved: every variant at every thread count on each frame (naive,
  // seconds a frame at 1080p, on scored frames only); the reference and the
  // scores on scored frames, at the largest thread count.
  Experiment experiment;
  experiment.set_reference({.renderer = &reference,
                            .name = "reference",
                            .warmup_draws = 0,
                            .read = ReadBack::kColorDepth});
  for (std::size_t v = 0; v < variants.size(); ++v)
    for (std::size_t t = 0; t < threads.size(); ++t)
      experiment.add({.renderer = renderers[v][t].get(),
                      .name = run_name(v, t),
                      .score = t == ti_max,
                      .every = variants[v] == VoxelVariant::kNaive ? o.score_every : 1,
                      // warm-up: thread pools, first touch (naive needs none)
                      .warmup_draws = variants[v] == VoxelVariant::kNaive ? 0 : 1});
  ExperimentOptions eo;
  eo.score_every = o.score_every;
  eo.scorer = [](const Frame& ref, const Frame& f) {
    QualityScore q;
    q.ssim = quality::ssim(ref.color.view(), f.color.view()).ssim;
    // The paper path's frames are mostly sky: also score the terrain alone.
    std::vector<std::uint8_t> terrain_mask(ref.depth.size());
    for (std::size_t k = 0; k < terrain_mask.size(); ++k)
      terrain_mask[k] = std::isfinite(ref.depth[k]);
    q.figures["ssim_terrain"] =
        quality::ssim(ref.color.view(), f.color.view(), {}, terrain_mask).ssim;
    q.psnr = std::min(quality::psnr(ref.color.view(), f.color.view()).rgb, kPsnrCapDb);
    q.flip = quality::flip(ref.color.view(), f.color.view()).mean;
    return q;
  };
  const std::string saved = run_name(2, ti_max);
  eo.on_frame = [&](int i, const std::string& name, const Frame& f) {
    if (name == "reference") save_png(f.color, out.file(fmt::format("reference_{:04d}.png", i)));
    if (name == saved && i % o.score_every == 0)
      save_png(f.color, out.file(fmt::format("multires_{:04d}.png", i)));
  };
  Progress progress("bench voxel");
  eo.progress = std::ref(progress);
  PathSource cameras(path);
  const ExperimentResult result = experiment.run(cameras, eo);

  // ms[v][t] over all frames drawn (naive: scored frames only); scored_ms[v]
  // at tmax over the scored frames.
  std::vector<std::vector<std::vector<double>>> ms(
      variants.size(), std::vector<std::vector<double>>(threads.size()));
  std::vector<std::vector<double>> scored_ms(variants.size());
  for (std::size_t v = 0; v < variants.size(); ++v)
    for (std::size_t t = 0; t < threads.size(); ++t)
      for (const FrameResult& f : result.run(run_name(v, t)).frames) {
        ms[v][t].push_back(f.ms);
        if (t == ti_max && f.quality) scored_ms[v].push_back(f.ms);
      }
  const RendererRun& ref_run = result.run("reference");
  std::vector<double> ref_ms;
  for (const FrameResult& f : ref_run.frames) ref_ms.push_back(f.ms);
  nlohmann::json per_frame = nlohmann::json::array();
  for (int i = 0; i < result.frames; ++i) per_frame.push_back({{"frame", i}});
  for (std::size_t v = 0; v < variants.size(); ++v)
    for (const FrameResult& f : result.run(run_name(v, ti_max)).frames) {
      per_frame[f.frame][std::string(to_string(variants[v])) + "_ms"] = f.ms;
      if (f.quality)
        per_frame[f.frame][std::string(to_string(variants[v])) + "_ssim"] = f.quality->ssim;
    }
  for (const FrameResult& f : ref_run.frames) per_frame[f.frame]["reference_ms"] = f.ms;
  auto quality_of = [&](std::size_t v, const std::string& metric) {
    return result.run(run_name(v, ti_max)).quality(metric);
  };

  auto scaling = [&](std::size_t v) -> double {
    auto one = std::find(threads.begin(), threads.end(), 1),
         two = std::find(threads.begin(), threads.end(), 2);
    if (one == threads.end() || two == threads.end()) return NAN;
    return median(ms[v][one - threads.begin()]) /
           std::max(median(ms[v][two - threads.begin()]), 1e-9);
  };
  const double naive_scored = median(scored_ms[0]);
  nlohmann::json jv = nlohmann::json::array();
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const double med = median(ms[v][ti_max]);
    jv.push_back({{"name", to_string(variants[v])},
                  {"threads", tmax},
                  {"frames_timed", ms[v][ti_max].size()},
                  {"median_ms", med},
                  {"p95_ms", percentile(ms[v][ti_max], 95)},
                  {"ns_per_pixel", med * 1e6 / (double(w) * h)},
                  {"speedup_vs_naive", naive_scored / std::max(median(scored_ms[v]), 1e-9)},
                  {"scaling_2v1", number_or_null(scaling(v))},
                  {"median_ms_by_threads",
                   [&] {
                     nlohmann::json m = nlohmann::json::object();
                     for (std::size_t t = 0; t < threads.size(); ++t)
                       m[std::to_string(threads[t])] = median(ms[v][t]);
                     return m;
                   }()},
                  {"mean_ssim", quality_of(v, "ssim").mean},
                  {"min_ssim", quality_of(v, "ssim").min},
                  {"mean_ssim_terrain", quality_of(v, "ssim_terrain").mean},
                  {"mean_psnr", quality_of(v, "psnr").mean},
                  {"mean_flip", quality_of(v, "flip").mean}});
  }

  // Static pitch sweep (paper Table 1): the default variant at each thread
  // count, five timed draws of each static view, thread counts interleaved.
  nlohmann::json pitch_table = nlohmann::json::array();
  for (double p : pitches) {
    Experiment table;
    for (std::size_t t = 0; t < threads.size(); ++t)
      table.add({.renderer = renderers[2][t].get(), .name = run_name(2, t)});
    PathSource view(std::vector<Camera>(5, pitch_camera(terrain.heights, p, double(w) / h)));
    ExperimentOptions to;
    to.warmup_draws = 1;
    const ExperimentResult r = table.run(view, to);
    for (std::size_t t = 0; t < threads.size(); ++t) {
      const double m = r.run(run_name(2, t)).ms().median;
      pitch_table.push_back({{"pitch_deg", p},
                             {"threads", threads[t]},
                             {"median_ms", m},
                             {"fps", 1000.0 / std::max(m, 1e-9)}});
    }
  }

  // Terrain size sweep: the same kind of path over synthetic terrains (no
  // erosion), each planned over its own terrain, the sizes interleaved frame
  // by frame so machine noise hits them alike.
  struct SweepEntry {
    int samples;
    std::unique_ptr<VoxelTerrain> voxels;
    std::unique_ptr<VoxelRenderer> renderer;
    std::vector<Camera> path;
  };
  std::vector<SweepEntry> entries;
  for (int n : sizes) {
    TerrainOptions to;
    to.synthetic_size = n;
    to.erosion_passes = 0;
    to.seed = o.terrain.seed;
    SweepEntry e;
    e.samples = n;
    {
      Terrain big = load_terrain(to);  // dropped once the pyramids are built
      e.voxels = std::make_unique<VoxelTerrain>(big);
      e.path = make_path(o.path, big.heights, std::max(1, std::min(o.sweep_frames, o.frames)),
                         double(w) / h);
    }
    VoxelOptions vo;
    vo.threads = tmax;
    vo.pixel_voxel_ratio = o.ratio;
    e.renderer = std::make_unique<VoxelRenderer>(*e.voxels, w, h, vo);
    entries.push_back(std::move(e));
  }
  nlohmann::json sweep = nlohmann::json::array();
  if (!entries.empty()) {
    Experiment by_size;
    for (const SweepEntry& e : entries)
      by_size.add({.renderer = e.renderer.get(),
                   .name = std::to_string(e.samples),
                   .camera_for = [&e](int i, const Camera&) { return e.path[std::size_t(i)]; }});
    PathSource frames(entries[0].path);  // the count; each size flies its own path
    const ExperimentResult r = by_size.run(frames, {});
    for (const SweepEntry& e : entries) {
      const Summary ms = r.run(std::to_string(e.samples)).ms();
      sweep.push_back({{"samples", e.samples},
                       {"frames", e.path.size()},
                       {"median_ms", ms.median},
                       {"p95_ms", ms.p95}});
    }
  }

  std::vector<std::string> names;
  std::vector<std::vector<double>> plot;
  for (std::size_t v = 1; v < variants.size(); ++v) {
    names.push_back(to_string(variants[v]));
    plot.push_back(ms[v][ti_max]);
  }
  write_plot(out, names, plot);

  const double default_scaling = scaling(2);
  nlohmann::json j = {
      {"device", fmt::format("cpu, {} hardware threads", std::thread::hardware_concurrency())},
      {"terrain", terrain_json(terrain)},
      {"size", {w, h}},
      {"path", o.path},
      {"frames", int(path.size())},
      {"score_every", o.score_every},
      {"scored_frames", ref_ms.size()},
      {"pixel_voxel_ratio", o.ratio},
      {"reference", {{"supersample", o.supersample}, {"median_ms", median(ref_ms)}}},
      {"threads", threads},
      {"default_variant", "multires"},
      {"variants", jv},
      {"scaling_2v1", number_or_null(default_scaling)},
      {"pitch_table", pitch_table},
      {"terrain_size_sweep", sweep},
      {"per_frame", per_frame}};
  write_json(j, out.file("bench_voxel.json"));  // JSON last: the directory is complete
  out.commit();
  if (!o.json.empty()) write_json(j, o.json);
  nlohmann::json summary = j;
  summary.erase("per_frame");
  fmt::print("{}\n", summary.dump(2));
}

}  // namespace

void add_bench_voxel(CLI::App& bench) {
  auto* cmd = bench.add_subcommand(
      "voxel", "CPU voxel ray caster: speed per variant, thread scaling, quality vs reference");
  auto o = std::make_shared<BenchVoxelOpts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--size", o->size, "image size WxH (default 1920x1080)");
  cmd->add_option("--path", o->path, "'paper' or a JSON path file");
  cmd->add_option("--frames", o->frames, "frames along the path (default 460)");
  cmd->add_option("--threads", o->threads, "thread counts to time, comma-separated (default 1,2)");
  cmd->add_option("--pitches", o->pitches, "static pitch sweep, degrees (default -10,-30,-60,-90)");
  cmd->add_option("--score-every", o->score_every,
                  "time naive and score against the reference every N-th frame (default 20)");
  cmd->add_option("--terrain-sizes", o->terrain_sizes,
                  "synthetic terrain sizes for the size sweep (default 1025,4097; 'none' to skip)");
  cmd->add_option("--sweep-frames", o->sweep_frames,
                  "frames per terrain in the size sweep (default 46)");
  cmd->add_option("--pixel-voxel-ratio", o->ratio,
                  "multires: coarsen where a voxel covers fewer pixels than this (default 1)");
  cmd->add_option("--supersample", o->supersample,
                  "reference rays per pixel side (default 2, i.e. 2x2)");
  cmd->add_option("--json", o->json, "also write the JSON here");
  cmd->add_option(
      "--out", o->out,
      "output directory: plot, reference and multires frames, JSON (default out/bench_voxel)");
  cmd->callback([o] { run(*o); });
}

}  // namespace terrasprite::cli
