// SPDX-License-Identifier: MIT
// terrasprite bench lodsprite: the LOD-sprite paper's reproduction benchmark:
// JSON, plots of its Figs. 8-12, images of its Figs. 13-14, index.html.
#include <fmt/format.h>

#include <cmath>

#include "bench_commands.h"
#include "cli_common.h"
#include "render_modes.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/lodsprite/lodsprite.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/lodsprite_json.h"
#include "terrasprite/report/lodsprite_report.h"

namespace terrasprite::cli {
namespace {

using lodsprite::LodspriteOptions;

template <typename T>
std::vector<T> list_of(const std::string& text, const char* option) {
  std::vector<T> out;
  for (double v : parse_list(text, option)) {
    if constexpr (std::is_integral_v<T>) {
      if (v != double(T(v)))
        throw InputError(fmt::format("{} {}: {} is not a whole number", option, text, v));
    }
    out.push_back(T(v));
  }
  return out;
}

// The command line as given; run_options() turns it into LodspriteOptions.
struct LodspriteBenchArgs {
  TerrainOptions terrain;
  LodspriteOptions config;
  std::string size = "512x512";
  std::string metric = "paper";
  std::string thresholds = "0.25,0.5,1,2,4,8";
  std::string frame_counts = "115,230,460,920,1840";
  std::string lod_sweep = "8,16,32,64";
  std::string out = "out/lodsprite";
  std::string json;
  double cache_mb = 0;
  std::string cache_policy = "lru";
  std::string mesh = "uniform";
  std::string shading = "plain";
};

// The keyframe triggers, the coarse mesh and the path.
void add_trigger_options(CLI::App& cmd, LodspriteBenchArgs& o) {
  cmd.add_option("--lod-quads", o.config.lod_quads, "coarse grid quads per side (default 16)");
  cmd.add_option("--mesh", o.mesh,
                 "the sprite's coarse mesh: uniform (default, the --lod-quads grid) | adaptive "
                 "(per keyframe, a screen-space-error quadtree for its camera)");
  cmd.add_option("--mesh-triangles", o.config.mesh_triangles,
                 "--mesh adaptive: triangle budget (default 0 = the uniform grid's 2 x "
                 "lod-quads^2, what plain LOD draws)");
  add_path_option(cmd, o.config.path);
  cmd.add_option("--frames", o.config.frames, "frames along the path (default 460)");
  cmd.add_option("--size", o.size, "image size WxH (default 512x512)");
  cmd.add_option("--threshold", o.config.threshold_px, "keyframe threshold, pixels (default 1.0)");
  cmd.add_option(
      "--metric", o.metric,
      "error metric that triggers keyframes: paper (default) | exact | contrast (predicted "
      "image error: --threshold in grey levels)");
  cmd.add_option("--fallback-trigger", o.config.max_fallback_fraction,
                 "also keyframe when this fraction of in-view quads fall back to the drape "
                 "texture (default 1 = off)");
  cmd.add_option("--scale-trigger", o.config.max_resample_scale,
                 "also keyframe when the keyframe's pixels are resampled by more than this factor "
                 "(default 1.25; inf = off)");
  cmd.add_option(
      "--scale-per-drape-px", o.config.scale_per_drape_px,
      "the scale trigger's limit rises to 1 + this x plain LOD's drape displacement "
      "(pixels) where that is higher (default 0.0625; 0 = the constant --scale-trigger)");
  cmd.add_flag("--scale-aniso", o.config.anisotropic_scale,
               "the scale trigger reads the keyframe's worst-stretched axis, not its area");
  cmd.add_option("--sharp-px", o.config.sharp_px,
                 "quads whose coarse geometry errs less than this many pixels take the drape "
                 "texture (default 0.5; 0 = off)");
  cmd.add_option("--key-margin", o.config.key_margin,
                 "keyframes see past the view by this fraction of its size on each side "
                 "(0..0.5, default 0): fewer quads fall back to the drape texture");
  cmd.add_option("--key-supersample", o.config.key_supersample,
                 "keyframes sample the view this many times more densely (1..2, default 1): "
                 "the scale trigger fires later");
  cmd.add_flag("--there-and-back", o.config.there_and_back,
               "fly the path there and back: its frames, then the same cameras reversed");
}

// The cache, the async display, shading, the comparisons, sweeps and outputs.
void add_pass_options(CLI::App& cmd, LodspriteBenchArgs& o) {
  cmd.add_flag_function(
      "--cache",
      [&o](std::int64_t) {
        if (o.cache_mb == 0) o.cache_mb = 256;
      },
      "keep past keyframes and reuse one when it fits the view (budget --cache-mb)");
  cmd.add_option("--cache-mb", o.cache_mb,
                 "keyframe cache budget in MB, colour + depth of every keyframe held "
                 "(default 256 with --cache; 0 = off)");
  cmd.add_option("--cache-accept", o.config.cache_accept,
                 "reuse a cached keyframe while its error is at most this fraction of the "
                 "threshold (default 0.5)");
  cmd.add_option("--cache-policy", o.cache_policy,
                 "which cached keyframe is evicted: lru (default) | farthest");
  cmd.add_flag("--async", o.config.async,
               "also fly the path as a simulated display with keyframes on a second thread "
               "(viewpoint prediction), beside the same display drawn synchronously");
  cmd.add_option("--display-hz", o.config.display_hz,
                 "--async: the simulated displays present on a clock of this rate (a frame not "
                 "ready by its slot is late and waits for the next; default 60; 0 = flat out)");
  cmd.add_option("--async-lead", o.config.async_lead,
                 "--async: also request a keyframe when the error predicted where it would land "
                 "exceeds this fraction of the threshold (default 0.6; 1 = at the threshold)");
  cmd.add_option("--shading", o.shading,
                 "terrain shading of every renderer: plain (default) | rich (soft shadows, "
                 "ambient occlusion and haze per fragment: full resolution pays it every frame, "
                 "LOD-sprite on keyframes)");
  cmd.add_flag("--compare-trigger", o.config.compare_trigger,
               "also compare the keyframe trigger with the other kind (geometric vs contrast, "
               "the predicted image error) at the same keyframe count");
  cmd.add_option("--thresholds", o.thresholds, "threshold sweep (default 0.25,0.5,1,2,4,8)");
  cmd.add_option("--frame-counts", o.frame_counts,
                 "frame-count sweep (default 115,230,460,920,1840)");
  cmd.add_option("--lod-sweep", o.lod_sweep,
                 "coarse-mesh sweep at the chosen threshold (default 8,16,32,64)");
  cmd.add_option("--sweep-score-every", o.config.sweep_score_every,
                 "sweeps score SSIM on every n-th frame (default 1)");
  cmd.add_option("--reference-every", o.config.reference_every,
                 "draw, time and score full resolution (and score plain LOD and the sprite) on "
                 "every n-th frame only (default 1); the full-resolution total is estimated as "
                 "their mean x frames; sprite and LOD frames are all drawn and timed");
  cmd.add_option("--out", o.out, "report directory (default out/lodsprite)");
  cmd.add_option("--json", o.json,
                 "also write the JSON here (stdout then gets a short summary, not the JSON)");
}

// The options the run needs from the command line; InputError for bad values.
LodspriteOptions run_options(const LodspriteBenchArgs& o) {
  LodspriteOptions c = o.config;
  std::tie(c.width, c.height) = parse_size(o.size, "--size");
  c.metric = lodsprite::parse_metric(o.metric);
  c.mesh = parse_mesh(o.mesh);
  check_mesh_triangles(c.mesh_triangles);
  c.shading = lodsprite::parse_shading(o.shading);
  if (!(o.cache_mb >= 0 && o.cache_mb <= 1 << 20))
    throw InputError(fmt::format("--cache-mb {}: must be between 0 and 1048576", o.cache_mb));
  c.cache_bytes = std::size_t(o.cache_mb * (1 << 20));
  c.cache_policy = lodsprite::parse_cache_policy(o.cache_policy);
  if (!(c.max_resample_scale >= 1.0))
    throw InputError(fmt::format("--scale-trigger {}: must be at least 1 (inf disables it)",
                                 c.max_resample_scale));
  if (!(c.scale_per_drape_px >= 0 && std::isfinite(c.scale_per_drape_px)))
    throw InputError(fmt::format("--scale-per-drape-px {}: must be a finite number, at least 0",
                                 c.scale_per_drape_px));
  c.thresholds = list_of<double>(o.thresholds, "--thresholds");
  c.frame_counts = list_of<int>(o.frame_counts, "--frame-counts");
  c.lod_sweep = list_of<int>(o.lod_sweep, "--lod-sweep");
  return c;
}

}  // namespace

void add_bench_lodsprite(CLI::App& bench, const OutputPolicy& policy) {
  auto* cmd = bench.add_subcommand("lodsprite",
                                   "LOD-sprite vs full resolution vs plain LOD: the paper's "
                                   "reproduction (JSON + plots + index.html)");
  auto o = std::make_shared<LodspriteBenchArgs>();
  add_terrain_options(*cmd, o->terrain);
  add_trigger_options(*cmd, *o);
  add_pass_options(*cmd, *o);
  cmd->callback([o, &policy] {
    LodspriteOptions c = run_options(*o);
    check_outputs(policy, o->out, {o->json});
    Terrain terrain = load_terrain_verbose(o->terrain);
    check_lod_quads(c.lod_quads, terrain.heights);
    for (int q : c.lod_sweep) check_lod_quads(q, terrain.heights, "--lod-sweep");
    OutputDir out(o->out, policy);
    c.progress = stage_progress("bench lodsprite");
    const lodsprite::LodspriteResult result = lodsprite::run_lodsprite(c, terrain);
    report::write_lodsprite_report(result, out);
    const nlohmann::json j = report::lodsprite_json(result);
    // JSON last: the directory is complete
    report::write_json(j, out.file("lodsprite.json"), policy);
    out.commit();
    if (!o->json.empty()) report::write_json(j, o->json, policy);
    nlohmann::json summary = j;
    summary.erase("per_frame");
    print_bench_result(
        summary, o->json,
        report::lodsprite_summary_text(result) + fmt::format("report: {}/index.html\n", o->out));
  });
}

}  // namespace terrasprite::cli
