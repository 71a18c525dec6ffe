// SPDX-License-Identifier: MIT
// `terrasprite bench hybrid`'s command line.
#include <memory>

#include "bench_commands.h"
#include "hybrid_bench_args.h"

namespace terrasprite::cli {

void add_bench_hybrid(CLI::App& bench) {
  auto* cmd = bench.add_subcommand(
      "hybrid", "objects under a frame-time budget: the hybrid walkthrough (Figures 4-6, Table 2)");
  auto a = std::make_shared<HybridArgs>();
  add_terrain_options(*cmd, a->terrain);
  cmd->add_option("--scene", a->scene,
                  "scene file (JSON); default: the built-in 400-instance scene");
  cmd->add_option("--models-dir", a->models_dir, "where the default scene's models are")
      ->capture_default_str();
  cmd->add_option("--instances", a->instances, "keep this many instances, drawn at random (0: all)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--target-ms", a->target,
                  "target frame time, ms, or auto: full geometry's median time on the frames "
                  "it is scored on (timed first) / --full-over-target, rounded down to 0.1 ms")
      ->capture_default_str();
  cmd->add_option("--full-over-target", a->full_over_target,
                  "auto target: full geometry's time over the target")
      ->capture_default_str();
  cmd->add_option("--size", a->size, "image size WxH")->capture_default_str();
  cmd->add_option("--cull-px", a->cull_px,
                  "budgeted scenarios may leave instances under this on-screen diameter (px) "
                  "undrawn when the budget cannot draw every one at its cheapest (0: never)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  cmd->add_option("--quality-spread-penalty", a->quality_spread_penalty,
                  "budgeted scenarios weigh an option at its expected SSIM less this many times "
                  "its table's spread near the view (0: as the tables say)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_flag("!--no-occlusion-cull", a->occlusion_cull,
                "draw instances hidden behind the terrain too (no depth read-back; no "
                "full-culled scenario)");
  cmd->add_option("--p95-margin", a->p95_margin,
                  "budgeted scenarios: standard errors of the controller's 160-frame p95 estimate "
                  "it keeps under the target (frame time first; 1 or 0: object quality first, "
                  "the p95 then lands nearer +10-15%)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--p95-aim", a->p95_aim,
                  "budgeted scenarios: where the controller aims the frames' p95, x the target "
                  "(before --p95-margin)")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 2.0));
  cmd->add_option("--pace-max-slope", a->pace_max_slope,
                  "with occlusion culling: the most the frame's prediction may follow the "
                  "read-back's pace (its log slope, fitted online; 0: not at all)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--llvmpipe-threads", a->llvmpipe_threads,
                  "llvmpipe's rasteriser threads (LP_NUM_THREADS; other drivers ignore it): a "
                  "count (0: on the drawing thread), driver (the environment's, else one per "
                  "core), or auto (the environment's if set, else 0 on at most 2 hardware "
                  "threads, where it keeps frame times tight)")
      ->capture_default_str();
  cmd->add_option("--msaa", a->msaa,
                  "samples a pixel (multisampled anti-aliasing) of every image the bench draws: "
                  "the tables, the cost calibration and every scenario, full geometry "
                  "included; 1 to what the GL offers (4 on llvmpipe; GL 4.5 offers at least "
                  "4). Without it, object SSIM on small objects measures where their aliased "
                  "edges fall: full geometry moved 1/16 pixel scored 0.91-0.94 on the forests")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  cmd->add_option("--frames", a->frames, "frames along the path")
      ->capture_default_str()
      ->check(CLI::Range(2, 100000));
  cmd->add_option("--score-every", a->score_every, "draw full geometry and score every n-th frame")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--path", a->path,
                  "JSON path file (with optional checkpoints); default: the walkthrough");
  cmd->add_option("--terrain-quads", a->terrain_quads, "terrain: coarse mesh quads per side")
      ->capture_default_str();
  cmd->add_option("--table-sizes", a->table_sizes, "quality tables: on-screen sizes, px")
      ->capture_default_str();
  cmd->add_option("--table-angle-step", a->table_angle_step,
                  "quality tables: degrees between views")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 180.0));
  cmd->add_option("--table-headings", a->table_headings,
                  "quality tables: model headings, degrees in [0, 360): the sun is fixed in the "
                  "world, so a heading says which side of the model it lights, and an instance "
                  "reads the tables between the two headings around its own")
      ->capture_default_str();
  cmd->add_option("--table-full-sphere", a->table_full_sphere,
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
  cmd->add_option("--quality-context-frames", a->quality_context_frames,
                  "the quality tables in context: rescale each representation's expected SSIM "
                  "to what it scores over the terrain in this many walkthrough views (0: the "
                  "tables as measured; with full-sphere tables it gains little: see the note)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--budget-sweep", a->budget_sweep,
                  "instead of the walkthrough: at each checkpoint, pm and mixed-optimal under "
                  "fixed budgets (--budget-fractions of full geometry's predicted frame), scored "
                  "and timed (JSON to this file)");
  cmd->add_option("--budget-fractions", a->budget_fractions, "for --budget-sweep")
      ->capture_default_str();
  cmd->add_option("--cost-split", a->cost_split,
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
  cmd->add_option("--diagnosis-images", a->diagnosis_images,
                  "for --quality-diagnosis: write the images of every instance drawn (existing "
                  "directory)");
  cmd->add_option("--figure6", a->figure6, "checkpoint shown in Figure 6")->capture_default_str();
  cmd->add_option("--cache", a->cache,
                  "quality-table and representation cache directory (default: "
                  "~/.cache/terrasprite/objects)");
  cmd->add_option("--json", a->json, "also write the JSON here");
  cmd->add_option("--out", a->out, "output directory (JSON, figures, index.html)")
      ->capture_default_str();
  cmd->callback([a] { run_bench_hybrid(*a); });
}

}  // namespace terrasprite::cli
