// SPDX-License-Identifier: MIT
// The hybrid walkthrough of Jehaes, Lamotte & Tack (GRAPP 2008, section 4)
// through the object scene: its setup (scene, path, quality tables, cost
// calibration, the target) and its scenarios interleaved frame by frame in
// one experiment.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>

#include "gl/render_target.h"
#include "hybrid_stages.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/hybrid/cost_calibration.h"
#include "terrasprite/hybrid/hybrid_renderer.h"
#include "terrasprite/objects/representation_cache.h"
#include "terrasprite/terrain/grid_mesh.h"

namespace terrasprite {
namespace {
using namespace hybrid_bench;

/// Keeps `count` instances (0: all), drawn at random (seeded) so the model mix stays.
void subsample(ObjectLayout& scene, int count) {
  if (count <= 0 || count >= int(scene.instances.size())) return;
  std::mt19937 rng(11);
  std::shuffle(scene.instances.begin(), scene.instances.end(), rng);
  scene.instances.resize(std::size_t(count));
}

/// Checkpoints moved onto the nearest scored frame.
std::vector<PathCheckpoint> snapped(std::vector<PathCheckpoint> cps, int score_every, int frames) {
  for (PathCheckpoint& c : cps) {
    c.frame = int(std::lround(double(c.frame) / score_every)) * score_every;
    while (c.frame >= frames) c.frame -= score_every;
    c.frame = std::max(0, c.frame);
  }
  return cps;
}

/// The scene and the path it is flown along, before any GL.
struct Walk {
  ObjectLayout scene;
  std::vector<Camera> path;
  std::vector<PathCheckpoint> checkpoints;  ///< on scored frames
};

/// The path file's keyframes, or the default walkthrough's over `drawn`.
KeyframePath path_keys(const HybridBenchOptions& o, const Terrain& terrain,
                       const std::function<double(double, double)>& drawn) {
  if (o.path_file.empty()) return walkthrough_path(terrain.heights, drawn);
  std::ifstream in(o.path_file);
  if (!in) throw InputError(fmt::format("--path {}: cannot read the file", o.path_file));
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_path_json(ss.str(), o.path_file);
}

Walk load_walk(const HybridBenchOptions& o, const Terrain& terrain) {
  Walk w;
  w.scene = o.scene_file.empty() ? default_object_layout(o.models_dir, terrain.heights)
                                 : load_object_layout(o.scene_file, terrain.heights);
  subsample(w.scene, o.instances);
  // The objects and the walkthrough stand on the terrain as drawn (the
  // coarse grid), not on the bilinear surface, which can lie far below it.
  const auto drawn = grid_surface(terrain.heights, o.terrain_quads);
  ground_instances(w.scene, drawn);
  const KeyframePath keys = path_keys(o, terrain, drawn);
  w.path = sample_path(keys, terrain.heights, o.frames, double(o.width) / o.height);
  if (o.path_file.empty()) keep_above_ground(w.path, drawn);
  w.checkpoints = snapped(checkpoint_frames(keys, o.frames), o.score_every, o.frames);
  return w;
}

/// Model i's table for one sampling, measured now (no cache).
QualityTable measured_table(GlSceneObjects& set, std::size_t i, const TableOptions& o) {
  return measure_quality_table(set.model(i), o);
}

/// Model i's table: each sampling from `source`, merged.
QualityTable model_table(GlSceneObjects& set, std::size_t i, const std::vector<TableOptions>& options,
                         const TableSource& source) {
  QualityTable merged;
  for (const TableOptions& o : options) {
    QualityTable t = source ? source(set, i, o) : measured_table(set, i, o);
    merged.model = t.model;
    merged.triangles = t.triangles;
    for (auto& r : t.representations) merged.representations.push_back(std::move(r));
  }
  return merged;
}

/// The cost model's terms per kind, fitted to the tables' measured draws.
DrawCostModel calibrated_cost(const std::vector<QualityTable>& tables) {
  std::array<std::vector<DrawSample>, 3> samples;
  for (const QualityTable& t : tables)
    for (const RepresentationQuality& r : t.representations)
      for (const SizeCost& c : r.cost)
        samples[std::size_t(r.rep.kind)].push_back(
            {1.0, 1.0, double(r.triangles), M_PI / 4 * c.size_px * c.size_px, c.ms_per_instance});
  // The tables time one instance per draw; instanced, most of that constant
  // is the draw call's.
  DrawCostModel m;
  for (int k = 0; k < 3; ++k) m.calibrate(ObjectKind(k), samples[std::size_t(k)], 0.9);
  return m;
}

/// The selection's options for every scenario (the target is set later).
/// Impostors are offered up to twice the tables' largest size, past which
/// their quality is extrapolated.
HybridOptions selection_options(const HybridBenchOptions& o,
                                const std::vector<TableOptions>& sampling) {
  HybridOptions ho;
  ho.width = o.width;
  ho.height = o.height;
  ho.cull_px = o.cull_px;
  ho.quality_spread_penalty = o.quality_spread_penalty;
  ho.controller.quantile_margin = o.p95_margin;
  ho.controller.tolerance = o.p95_aim;
  ho.pace.max_slope = o.pace_max_slope;
  for (const TableOptions& t : sampling)
    for (int px : t.sizes_px) ho.max_impostor_size_px = std::max(ho.max_impostor_size_px, 2.0 * px);
  return ho;
}

/// The tables in context: rescaled by what each representation scores over
/// the terrain in `n` walkthrough frames spread along `path`, none within a
/// frame of a checkpoint. Prints the median error scale per kind on stderr.
std::vector<ContextCalibration> tables_in_context(QualityContextInput qi, const Walk& walk, int n,
                                                  std::vector<QualityTable>& tables) {
  const int frames = int(walk.path.size());
  auto near_checkpoint = [&](int f) {
    return std::any_of(walk.checkpoints.begin(), walk.checkpoints.end(),
                       [&](const PathCheckpoint& c) { return std::abs(c.frame - f) <= 1; });
  };
  for (int k = 0; k < n; ++k) {
    int f = int(std::lround((k + 0.5) * (frames - 1) / n));
    for (int step = 0; step < frames && near_checkpoint(f); ++step) f = (f + 1) % frames;
    qi.cameras.push_back(walk.path[std::size_t(f)]);
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<ContextCalibration> report = calibrate_tables_in_context(qi, tables);
  std::map<std::string, std::vector<double>> by_kind;
  for (const ContextCalibration& row : report)
    by_kind[object_kind_name(row.kind)].push_back(row.error_scale);
  std::string line;
  for (auto& [kind, v] : by_kind) line += fmt::format(" {} {:.2f},", kind, summarize(v).median);
  fmt::print(stderr,
             "quality tables in context ({} views, {:.1f} s): median error scale per kind:{}\n", n,
             std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), line);
  return report;
}

/// The tables time small sizes in a small image; the walkthrough draws
/// instances up to larger than the image: every representation timed at
/// `sizes_px` in an image of the frames' size, and `cost` fitted per kind.
/// Returns the calibration's report.
std::string calibrate_for_walk(GlSceneObjects& set, const std::vector<QualityTable>& tables, int w,
                               int h, int samples, double fov_y_deg,
                               const std::vector<int>& sizes_px, DrawCostModel& cost) {
  CostCalibrationOptions co;
  co.width = w;
  co.height = h;
  co.samples = samples;
  co.fov_y_deg = fov_y_deg;
  co.sizes_px = sizes_px;
  std::vector<std::vector<Representation>> reps(set.model_count());
  for (std::size_t m = 0; m < set.model_count(); ++m)
    for (const RepresentationQuality& r : tables[m].representations) reps[m].push_back(r.rep);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<CalibrationDraw> draws = measure_draw_costs(set, reps, co);
  fmt::print(stderr, "cost model from the tables' draws only: {}", calibration_report(cost, draws));
  fit_draw_costs(cost, draws);
  std::string report = calibration_report(cost, draws);
  fmt::print(stderr, "after calibration ({} draws, {:.1f} s): {}", draws.size(),
             std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), report);
  return report;
}

/// The cost calibration's sizes: as given, or image height / 8, / 2 and x 2.
std::vector<int> calibration_sizes(const HybridBenchOptions& o) {
  if (!o.calibration_sizes.empty()) return o.calibration_sizes;
  const int h = o.height;
  return {std::max(8, h / 8), std::max(16, h / 2), 2 * h};
}

/// The terrain alone, median of six frames spread along the path (ms).
double terrain_alone_ms(HybridRenderer& terrain_only, const std::vector<Camera>& path) {
  std::vector<double> ms;
  for (int k = 0; k < 6; ++k)
    ms.push_back(terrain_only.draw(path[std::size_t(k * (path.size() - 1) / 5)]).ms);
  return summarize(ms).median;
}

/// `full`'s frame time (ms) before the walk, on the frames the run scores
/// full geometry on (every `score_every`-th), so that the auto target
/// follows the run's own sample. Twelve unmeasured draws first (the first
/// draws of each mesh are slow: uploads, first-use faults); then two timed
/// passes, the lower median kept, so a slow spell of the host during one
/// pass does not set the target.
double timed_full_ms(HybridRenderer& full, const std::vector<Camera>& path, int score_every) {
  for (int k = 0; k < 12; ++k) full.draw(path[std::size_t(k * (path.size() - 1) / 11)]);
  double best = std::numeric_limits<double>::infinity();
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<double> ms;
    for (std::size_t f = 0; f < path.size(); f += std::size_t(score_every))
      ms.push_back(full.draw(path[f]).ms);
    best = std::min(best, summarize(ms).median);
  }
  return best;
}

/// What every stage after the setup shares: the options, the terrain as
/// drawn, the objects with their tables and cost model, the walk.
struct Bench {
  const HybridBenchOptions& o;
  Scene& ground;
  GlSceneObjects& set;
  const std::vector<QualityTable>& tables;
  const DrawCostModel& cost;
  const Walk& walk;
};

/// The frame-time target: as given, or auto (full geometry timed over the
/// scored frames, over full_over_target, rounded down to 0.1 ms). Sets the
/// result's full_ms_at_start, target_auto and target_ms.
void decide_target(const Bench& b, const HybridOptions& ho, HybridBenchResult& result) {
  const HybridBenchOptions& o = b.o;
  {
    HybridObjects full_objects(b.set, b.tables, b.cost, walk_scenario(WalkScenario::kFull, false),
                               ho);
    HybridRenderer full_only(b.ground, &full_objects, "full", o.width, o.height, o.terrain_quads,
                             o.msaa);
    result.full_ms_at_start = timed_full_ms(full_only, b.walk.path, o.score_every);
  }
  result.target_auto = !o.target_ms;
  result.target_ms =
      o.target_ms ? *o.target_ms
                  : std::max(0.1, std::floor(10 * result.full_ms_at_start / o.full_over_target) / 10);
  fmt::print(stderr,
             "terrain alone {:.1f} ms (median of 6 path frames), full geometry {:.1f} ms (the "
             "lower of two medians of the scored frames); target {:g} ms{}\n",
             result.terrain_ms, result.full_ms_at_start, result.target_ms,
             result.target_auto ? fmt::format(" (auto: full / {:g})", o.full_over_target) : "");
}

/// The scenarios' selection and drawing, one renderer each (objects first:
/// the renderer draws them).
struct Scenarios {
  std::vector<WalkScenario> ids;
  std::vector<std::unique_ptr<HybridObjects>> objects;
  std::vector<std::unique_ptr<HybridRenderer>> renderers;
  /// Per scenario, the selection's figures by frame number.
  std::vector<std::map<int, HybridFrameStats>> selection;
};

Scenarios make_scenarios(const Bench& b, const HybridOptions& ho) {
  Scenarios s;
  s.ids = walk_scenarios(b.o.occlusion_cull);
  for (WalkScenario id : s.ids) {
    const HybridScenario sc = walk_scenario(id, b.o.occlusion_cull);
    s.objects.push_back(std::make_unique<HybridObjects>(b.set, b.tables, b.cost, sc, ho));
    s.objects.back()->prepare();
    s.renderers.push_back(std::make_unique<HybridRenderer>(
        b.ground, s.objects.back().get(), sc.name, b.o.width, b.o.height, b.o.terrain_quads,
        b.o.msaa));
  }
  s.selection.resize(s.ids.size());
  return s;
}

/// The experiment: full geometry the reference, the terrain alone on scored
/// frames (the object mask's depth), the other scenarios scored and taking
/// turns in the frame's order (Participant::rotate), since a draw's time
/// depends on what ran just before it.
Experiment walk_experiment(Scenarios& s, HybridRenderer& terrain_only, int score_every) {
  Experiment experiment;
  auto annotate = [&s](std::size_t k) {
    return [o = s.objects[k].get(), &sink = s.selection[k]](const Frame&, FrameResult& r) {
      sink[r.frame] = o->last();
    };
  };
  Participant ref{.renderer = s.renderers[0].get(), .name = "full", .read = ReadBack::kColorDepth};
  ref.annotate = annotate(0);
  experiment.set_reference(ref);
  experiment.add(
      {.renderer = &terrain_only, .name = "terrain", .every = score_every, .read = ReadBack::kDepth});
  for (std::size_t k = 1; k < s.renderers.size(); ++k) {
    Participant p{.renderer = s.renderers[k].get(),
                  .name = s.renderers[k]->name(),
                  .score = true,
                  .read = ReadBack::kDepth,
                  .rotate = true};
    p.annotate = annotate(k);
    // The warm-up draw is untimed and cold: it must not set the first
    // timed frame's budget (a checkpoint may be frame 0).
    p.after_warmup = [o = s.objects[k].get()] { o->forget_feedback(); };
    experiment.add(p);
  }
  return experiment;
}

/// The walkthrough itself: every scenario along the path, scored against
/// full geometry; fills the result's scenarios, selection and Figure 6.
void run_walkthrough(const Bench& b, const HybridOptions& ho, HybridRenderer& terrain_only,
                     const std::function<void(int, int)>& progress, HybridBenchResult& result) {
  Scenarios s = make_scenarios(b, ho);
  const std::vector<PathCheckpoint>& checkpoints = b.walk.checkpoints;
  auto state = std::make_shared<ScoringState>();
  for (const PathCheckpoint& c : checkpoints) state->flip_frames.push_back(c.frame);
  const auto fig6 = std::find_if(checkpoints.begin(), checkpoints.end(),
                                 [&](const PathCheckpoint& c) { return c.name == b.o.figure6; });
  const int fig6_frame = fig6 != checkpoints.end() ? fig6->frame : -1;
  result.figure6_checkpoint = fig6 != checkpoints.end() ? fig6->name : "";

  Experiment experiment = walk_experiment(s, terrain_only, b.o.score_every);
  ExperimentOptions eo;
  eo.score_every = b.o.score_every;
  eo.scorer = hybrid_scorer(state);
  eo.progress = progress;
  eo.on_frame = [&](int frame, const std::string& name, const Frame& f) {
    state->frame = frame;
    if (name == "terrain") state->terrain_depth = f.depth;
    if (frame != fig6_frame) return;
    if (const std::optional<WalkScenario> id = parse_walk_scenario(name))
      result.figure6.push_back({*id, f.color});
  };
  PathSource cameras(b.walk.path);
  const ExperimentResult r = experiment.run(cameras, eo);
  result.frames = r.frames;
  for (std::size_t k = 0; k < s.ids.size(); ++k) {
    const RendererRun& run = r.run(walk_scenario_name(s.ids[k]));
    result.scenarios.push_back(summarise(s.ids[k], hybrid_frames(run, s.selection[k]),
                                         result.target_ms, checkpoints));
  }
  // Drawn in turns: back to the scenarios' order (full first).
  std::stable_sort(result.figure6.begin(), result.figure6.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  result.selection = selection_figures(result.scenario(WalkScenario::kMixedOptimal)->frames);
}

/// Quality against fixed budgets at each checkpoint (pm and mixed-optimal).
std::vector<BudgetSweepRow> budget_sweep(const Bench& b, const HybridOptions& ho,
                                         const std::vector<QualityTable>* raw_tables) {
  std::vector<HybridScenario> swept;
  for (WalkScenario id : {WalkScenario::kPm, WalkScenario::kMixedOptimal})
    swept.push_back(walk_scenario(id, b.o.occlusion_cull));
  return quality_budget_sweep({b.set, b.tables, b.cost, b.ground, b.walk.path,
                               b.walk.checkpoints, b.o.width, b.o.height, b.o.terrain_quads, ho,
                               swept, b.o.budget_fractions, raw_tables, b.o.cost_split, b.o.msaa});
}

}  // namespace

std::vector<TableOptions> hybrid_table_options(const HybridBenchOptions& o) {
  const std::pair<std::vector<ObjectKind>, const std::vector<int>*> parts[] = {
      {{ObjectKind::kMesh, ObjectKind::kRelief}, &o.relief_resolutions},
      {{ObjectKind::kOctahedral}, &o.octahedral_resolutions}};
  std::vector<TableOptions> out;
  for (const auto& [kinds, resolutions] : parts) {
    TableOptions t;
    t.kinds = kinds;
    t.resolutions = *resolutions;
    t.sizes_px = o.table_sizes;
    t.angle_step_deg = o.table_angle_step;
    t.headings_deg = o.table_headings;
    t.full_sphere = o.table_full_sphere;
    t.samples = o.msaa;
    out.push_back(std::move(t));
  }
  return out;
}

HybridBenchResult run_hybrid(const HybridBenchOptions& o, const HybridBenchInputs& in) {
  const std::vector<TableOptions> table_sampling = hybrid_table_options(o);
  const Walk walk = load_walk(o, in.terrain);
  GlContext gl;
  if (o.msaa > gl::max_samples())
    throw InputError(fmt::format("--msaa {}: this GL offers at most {} samples a pixel", o.msaa,
                                 gl::max_samples()));
  Scene ground(in.terrain);
  ground.prepare(o.terrain_quads);
  GlSceneObjects set(walk.scene, LodOptions{}, o.cache_dir.empty() ? default_cache_dir() : o.cache_dir);
  HybridBenchResult result;
  result.mode = o.mode;
  std::vector<QualityTable> tables;
  for (std::size_t i = 0; i < set.model_count(); ++i)
    tables.push_back(model_table(set, i, table_sampling, in.tables));
  HybridOptions ho = selection_options(o, table_sampling);
  const std::vector<QualityTable> tables_as_measured = tables;
  const bool in_context = o.quality_context_frames > 0;
  if (in_context)
    result.quality_context = tables_in_context(
        {set, ground, {}, o.width, o.height, o.terrain_quads, ho.max_impostor_size_px, o.msaa},
        walk, o.quality_context_frames, tables);
  if (o.mode == HybridMode::kQualityDiagnosis) {
    result.quality_diagnosis = diagnose_hybrid_quality(
        {set, tables_as_measured, ground, walk.path, walk.checkpoints, o.width, o.height,
         o.terrain_quads, o.diagnosis_conditions, o.diagnosis_images,
         in_context ? &tables : nullptr, o.msaa});
    return result;
  }
  DrawCostModel cost = calibrated_cost(tables);
  result.calibration = calibrate_for_walk(set, tables, o.width, o.height, o.msaa,
                                          walk.path.front().fov_y_deg, calibration_sizes(o), cost);
  result.gl_renderer = gl.renderer();
  result.llvmpipe_threads = o.llvmpipe_threads;
  result.msaa = o.msaa;
  result.width = o.width;
  result.height = o.height;
  result.instances = int(set.instance_count());
  result.full_triangles_max = set.full_triangles();
  result.score_every = o.score_every;
  result.full_over_target = o.full_over_target;

  // The terrain alone: the cost model's fixed term, and the object mask.
  HybridRenderer terrain_only(ground, nullptr, "terrain", o.width, o.height, o.terrain_quads,
                              o.msaa);
  result.terrain_ms = terrain_alone_ms(terrain_only, walk.path);
  cost.set_frame_ms(result.terrain_ms);
  const Bench bench{o, ground, set, tables, cost, walk};
  if (o.mode == HybridMode::kBudgetSweep) {
    result.budget_sweep = budget_sweep(bench, ho, in_context ? &tables_as_measured : nullptr);
    return result;
  }
  decide_target(bench, ho, result);
  ho.target_ms = result.target_ms;
  run_walkthrough(bench, ho, terrain_only, in.progress, result);
  return result;
}

}  // namespace terrasprite
