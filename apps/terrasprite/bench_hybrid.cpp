// SPDX-License-Identifier: MIT
// `terrasprite bench hybrid`: its options parsed into HybridBenchOptions,
// the run (experiment/hybrid/hybrid.h), its report written.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "bench_commands.h"
#include "cli_common.h"
#include "llvmpipe_threads.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/hybrid/hybrid.h"
#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/quality_table_cache.h"
#include "terrasprite/objects/quality_table_json.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/report/hybrid_report.h"
#include "terrasprite/report/json_writer.h"

namespace terrasprite::cli {
namespace {

/// Comma-separated values as the command line shows them.
template <class T>
std::string comma_list(const std::vector<T>& v) {
  return fmt::format("{}", fmt::join(v, ","));
}

/// The command line: the typed options, bound where CLI11 parses them as
/// they are; the text of what is parsed and checked here (sizes, lists,
/// the target), and the outputs.
struct HybridCommand {
  TerrainOptions terrain;
  HybridBenchOptions o;
  std::string size = "320x180", target = "auto";
  std::string table_sizes = comma_list(o.table_sizes);
  std::string relief_resolutions = comma_list(o.relief_resolutions);
  std::string octahedral_resolutions = comma_list(o.octahedral_resolutions);
  std::string table_headings = comma_list(o.table_headings);
  std::string calibration_sizes = "auto";
  std::string budget_fractions = comma_list(o.budget_fractions);
  std::string diagnosis_conditions = "scene,sky";
  std::string llvmpipe_threads = "auto";
  std::string json, out = "out/bench_hybrid", budget_sweep, quality_diagnosis;
};

/// `text` as a number when all of it is one (std::stod accepts "1x" as 1).
std::optional<double> whole_number_text(const std::string& text) {
  std::size_t used = 0;
  try {
    const double v = std::stod(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

std::vector<DiagnosisCondition> diagnosis_conditions(const std::string& text) {
  std::vector<DiagnosisCondition> out;
  for (const std::string& k : split_list(text)) {
    const std::optional<DiagnosisCondition> c = parse_diagnosis_condition(k);
    if (!c)
      throw InputError(fmt::format("--diagnosis-conditions: '{}' is not scene, sky or scene4", k));
    out.push_back(*c);
  }
  return out;
}

std::vector<double> budget_fractions(const std::string& text) {
  std::vector<double> out;
  for (const std::string& f : split_list(text)) {
    const std::optional<double> v = whole_number_text(f);
    if (!v || !(*v > 0 && *v <= 4))
      throw InputError(fmt::format("--budget-fractions: '{}' is not a number in (0, 4]", f));
    out.push_back(*v);
  }
  return out;
}

std::optional<double> target_ms(const std::string& text) {
  if (text == "auto") return std::nullopt;
  const std::optional<double> t = whole_number_text(text);
  if (!t || !(*t > 0) || !std::isfinite(*t))
    throw InputError(
        fmt::format("--target-ms {}: not a positive number of milliseconds or auto", text));
  return t;
}

/// --calibration-sizes: the list, or auto (image height / 8, / 2 and x 2).
std::vector<int> calibration_sizes(const std::string& text, int h) {
  const std::vector<int> sizes =
      text == "auto" ? std::vector<int>{std::max(8, h / 8), std::max(16, h / 2), 2 * h}
                     : int_list(text, "--calibration-sizes");
  for (int px : sizes)
    if (px < 4 || px > 8192)
      throw InputError(fmt::format("--calibration-sizes: {} is outside 4..8192", px));
  return sizes;
}

/// The options checked before any work (the tables take minutes when not
/// cached): every value is turned into its typed field or an InputError.
void check_options(HybridCommand& c, const OutputPolicy& policy) {
  HybridBenchOptions& o = c.o;
  std::tie(o.width, o.height) = parse_size(c.size, "--size");
  check_outputs(policy, c.out, {c.json, c.quality_diagnosis, c.budget_sweep});
  o.diagnosis_conditions = diagnosis_conditions(c.diagnosis_conditions);
  o.budget_fractions = budget_fractions(c.budget_fractions);
  if (o.cost_split > 0 && c.budget_sweep.empty())
    throw InputError("--cost-split: only with --budget-sweep");
  o.target_ms = target_ms(c.target);
  if (!(o.full_over_target >= 1)) throw InputError("--full-over-target must be at least 1");
  o.calibration_sizes = calibration_sizes(c.calibration_sizes, o.height);
  o.mode = !c.quality_diagnosis.empty() ? HybridMode::kQualityDiagnosis
           : !c.budget_sweep.empty()    ? HybridMode::kBudgetSweep
                                        : HybridMode::kWalkthrough;
}

/// Throws InputError unless every impostor resolution is in 16..512 texels.
void check_resolutions(const std::vector<int>& r, const char* option) {
  for (int x : r)
    if (x < 16 || x > 512) throw InputError(fmt::format("{}: {} is outside 16..512", option, x));
}

/// The quality tables' sampling lists, checked in the order the two
/// samplings (meshes and relief, then octahedral) read them.
void check_table_options(HybridCommand& c) {
  HybridBenchOptions& o = c.o;
  o.relief_resolutions = int_list(c.relief_resolutions, "--relief-resolutions");
  o.table_sizes = int_list(c.table_sizes, "--table-sizes");
  o.table_headings = parse_list(c.table_headings, "--table-headings");
  check_headings(o.table_headings, "--table-headings");
  check_resolutions(o.relief_resolutions, "--relief-resolutions");
  for (int px : o.table_sizes)
    if (px < kMinTableSizePx || px > kMaxTableSizePx)
      throw InputError(
          fmt::format("--table-sizes: {} is outside {}..{}", px, kMinTableSizePx, kMaxTableSizePx));
  o.octahedral_resolutions = int_list(c.octahedral_resolutions, "--octahedral-resolutions");
  check_resolutions(o.octahedral_resolutions, "--octahedral-resolutions");
}

/// Model i's table for one sampling, from the table cache in `cache` (empty:
/// the default) or measured now and cached.
QualityTable cached_table(GlSceneObjects& set, std::size_t i, const TableOptions& o,
                          const std::string& cache) {
  const LayoutModel& sm = set.layout_model(i);
  const TableCacheEntry entry = table_cache_entry(cache, sm.file, set.model(i).model(), sm.options,
                                                  o, lod_chain_key(set.lod()));
  std::optional<QualityTable> t = read_table_cache(entry);
  if (!t) {
    fmt::print(stderr, "measuring the quality table of {} ({})\n", sm.name,
               o.kinds.size() > 1 ? "pm, relief" : "octahedral");
    Progress progress("table " + sm.name);
    t = measure_quality_table(set.model(i), o, [&](int d, int n) { progress(d, n); });
    write_table_cache(entry, table_json(*t, o));
  }
  return *t;
}

void run_bench_hybrid(HybridCommand& c, const OutputPolicy& policy) {
  check_options(c, policy);
  // Before the run's GL context, the first of this process.
  c.o.llvmpipe_threads = apply_llvmpipe_threads(c.llvmpipe_threads, "--llvmpipe-threads");
  check_table_options(c);
  const Terrain terrain = load_terrain_verbose(c.terrain);
  check_lod_quads(c.o.terrain_quads, terrain.heights, "--terrain-quads");
  OutputDir out(c.out, policy);
  Progress progress("bench hybrid");
  const std::string cache = c.o.cache_dir;
  const HybridBenchResult r =
      run_hybrid(c.o, {terrain,
                       [&](GlSceneObjects& set, std::size_t i, const TableOptions& o) {
                         return cached_table(set, i, o, cache);
                       },
                       std::ref(progress)});
  switch (r.mode) {
    case HybridMode::kQualityDiagnosis:
      return report::write_json(report::quality_diagnosis_json(r.quality_diagnosis),
                                c.quality_diagnosis, policy);
    case HybridMode::kBudgetSweep:
      return report::write_json(report::budget_sweep_json(r.budget_sweep), c.budget_sweep, policy);
    case HybridMode::kWalkthrough:
      break;
  }
  const nlohmann::json j = report::hybrid_json(r);
  report::write_hybrid_report(r, out);
  report::write_json(j, out.file("hybrid.json"), policy);
  if (!c.json.empty()) report::write_json(j, c.json, policy);
  out.commit();
  fmt::print("{}\n{}", report::table2_markdown(r), report::hybrid_summary_text(r));
}

/// The scene, the target and the image.
void add_walk_options(CLI::App* cmd, HybridCommand* a) {
  HybridBenchOptions* o = &a->o;
  cmd->add_option("--scene", o->scene_file,
                  "scene file (JSON); default: the built-in 400-instance scene");
  cmd->add_option("--models-dir", o->models_dir, "where the default scene's models are")
      ->capture_default_str();
  cmd->add_option("--instances", o->instances, "keep this many instances, drawn at random (0: all)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--target-ms", a->target,
                  "target frame time, ms, or auto: full geometry's median time on the frames "
                  "it is scored on (timed first) / --full-over-target, rounded down to 0.1 ms")
      ->capture_default_str();
  cmd->add_option("--full-over-target", o->full_over_target,
                  "auto target: full geometry's time over the target")
      ->capture_default_str();
  cmd->add_option("--size", a->size, "image size WxH")->capture_default_str();
}

/// How the budgeted scenarios select and hold their frame time.
void add_selection_options(CLI::App* cmd, HybridBenchOptions* o) {
  cmd->add_option("--cull-px", o->cull_px,
                  "budgeted scenarios may leave instances under this on-screen diameter (px) "
                  "undrawn when the budget cannot draw every one at its cheapest (0: never)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  cmd->add_option("--quality-spread-penalty", o->quality_spread_penalty,
                  "budgeted scenarios weigh an option at its expected SSIM less this many times "
                  "its table's spread near the view (0: as the tables say)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_flag("!--no-occlusion-cull", o->occlusion_cull,
                "draw instances hidden behind the terrain too (no depth read-back; no "
                "full-culled scenario)");
  cmd->add_option("--p95-margin", o->p95_margin,
                  "budgeted scenarios: standard errors of the controller's 160-frame p95 estimate "
                  "it keeps under the target (frame time first; 1 or 0: object quality first, "
                  "the p95 then lands nearer +10-15%)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--p95-aim", o->p95_aim,
                  "budgeted scenarios: where the controller aims the frames' p95, x the target "
                  "(before --p95-margin)")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 2.0));
  cmd->add_option("--pace-max-slope", o->pace_max_slope,
                  "with occlusion culling: the most the frame's prediction may follow the "
                  "read-back's pace (its log slope, fitted online; 0: not at all)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
}

/// How every image is drawn, and where along which path.
void add_drawing_options(CLI::App* cmd, HybridCommand* a) {
  HybridBenchOptions* o = &a->o;
  cmd->add_option("--llvmpipe-threads", a->llvmpipe_threads,
                  "llvmpipe's rasteriser threads (LP_NUM_THREADS; other drivers ignore it): a "
                  "count (0: on the drawing thread), driver (the environment's, else one per "
                  "core), or auto (the environment's if set, else 0 on at most 2 hardware "
                  "threads, where it keeps frame times tight)")
      ->capture_default_str();
  cmd->add_option("--msaa", o->msaa,
                  "samples a pixel (multisampled anti-aliasing) of every image the bench draws: "
                  "the tables, the cost calibration and every scenario, full geometry "
                  "included; 1 to what the GL offers (4 on llvmpipe; GL 4.5 offers at least "
                  "4). Without it, object SSIM on small objects measures where their aliased "
                  "edges fall: full geometry moved 1/16 pixel scored 0.91-0.94 on the forests")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  cmd->add_option("--frames", o->frames, "frames along the path")
      ->capture_default_str()
      ->check(CLI::Range(2, 100000));
  cmd->add_option("--score-every", o->score_every, "draw full geometry and score every n-th frame")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--path", o->path_file,
                  "JSON path file (with optional checkpoints); default: the walkthrough");
  cmd->add_option("--terrain-quads", o->terrain_quads, "terrain: coarse mesh quads per side")
      ->capture_default_str();
}

/// The quality tables' sampling and the cost calibration's sizes.
void add_table_options(CLI::App* cmd, HybridCommand* a) {
  HybridBenchOptions* o = &a->o;
  cmd->add_option("--table-sizes", a->table_sizes, "quality tables: on-screen sizes, px")
      ->capture_default_str();
  cmd->add_option("--table-angle-step", o->table_angle_step,
                  "quality tables: degrees between views")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 180.0));
  cmd->add_option("--table-headings", a->table_headings,
                  "quality tables: model headings, degrees in [0, 360): the sun is fixed in the "
                  "world, so a heading says which side of the model it lights, and an instance "
                  "reads the tables between the two headings around its own")
      ->capture_default_str();
  cmd->add_option("--table-full-sphere", o->table_full_sphere,
                  "quality tables: views from below too (theta to 180): the walkthrough sees "
                  "most instances from 18-28 degrees below their centre, and hemisphere tables "
                  "clamped there mispredicted every kind")
      ->capture_default_str();
  cmd->add_option("--relief-resolutions", a->relief_resolutions, "relief impostor resolutions")
      ->capture_default_str();
  cmd->add_option("--octahedral-resolutions", a->octahedral_resolutions,
                  "octahedral impostor resolutions")
      ->capture_default_str();
  cmd->add_option("--calibration-sizes", a->calibration_sizes,
                  "cost calibration: on-screen sizes, px (each representation timed alone); auto: "
                  "image height / 8, / 2 and x 2")
      ->capture_default_str();
  cmd->add_option("--quality-context-frames", o->quality_context_frames,
                  "the quality tables in context: rescale each representation's expected SSIM "
                  "to what it scores over the terrain in this many walkthrough views (0: the "
                  "tables as measured; with full-sphere tables it gains little: see the note)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
}

/// The budget sweep and the quality diagnosis (instead of the walkthrough).
void add_side_study_options(CLI::App* cmd, HybridCommand* a) {
  HybridBenchOptions* o = &a->o;
  cmd->add_option("--budget-sweep", a->budget_sweep,
                  "instead of the walkthrough: at each checkpoint, pm and mixed-optimal under "
                  "fixed budgets (--budget-fractions of full geometry's predicted frame), scored "
                  "and timed (JSON to this file)");
  cmd->add_option("--budget-fractions", a->budget_fractions, "for --budget-sweep")
      ->capture_default_str();
  cmd->add_option("--cost-split", o->cost_split,
                  "for --budget-sweep: also time each frame split by kind, over this many "
                  "interleaved rounds of redraws (each kind alone over the terrain and its "
                  "share of the whole frame, against its prediction; 0: not)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--quality-diagnosis", a->quality_diagnosis,
                  "instead of the walkthrough: per checkpoint, size bucket and representation, "
                  "the tables' predicted SSIM against the measured one (JSON to this file)");
  cmd->add_option("--diagnosis-conditions", a->diagnosis_conditions,
                  "for --quality-diagnosis: scene, sky, scene4 (comma-separated)")
      ->capture_default_str();
  cmd->add_option("--diagnosis-images", o->diagnosis_images,
                  "for --quality-diagnosis: write the images of every instance drawn (existing "
                  "directory)");
}

/// Figure 6's checkpoint, the caches and the outputs.
void add_output_options(CLI::App* cmd, HybridCommand* a) {
  HybridBenchOptions* o = &a->o;
  cmd->add_option("--figure6", o->figure6, "checkpoint shown in Figure 6")->capture_default_str();
  cmd->add_option("--cache", o->cache_dir,
                  "quality-table and representation cache directory (default: "
                  "~/.cache/terrasprite/objects)");
  cmd->add_option("--json", a->json, "also write the JSON here");
  cmd->add_option("--out", a->out, "output directory (JSON, figures, index.html)")
      ->capture_default_str();
}

}  // namespace

void add_bench_hybrid(CLI::App& bench, const OutputPolicy& policy) {
  auto* cmd = bench.add_subcommand(
      "hybrid", "objects under a frame-time budget: the hybrid walkthrough (Figures 4-6, Table 2)");
  auto c = std::make_shared<HybridCommand>();
  add_terrain_options(*cmd, c->terrain);
  add_walk_options(cmd, c.get());
  add_selection_options(cmd, &c->o);
  add_drawing_options(cmd, c.get());
  add_table_options(cmd, c.get());
  add_side_study_options(cmd, c.get());
  add_output_options(cmd, c.get());
  cmd->callback([c, &policy] { run_bench_hybrid(*c, policy); });
}

}  // namespace terrasprite::cli
