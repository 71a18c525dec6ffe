// SPDX-License-Identifier: MIT
// terrasprite view: fly the terrain in a window, or replay a timed script of
// input events and measure frame rate and input-to-display latency.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>

#include "cli_common.h"
#include "commands.h"
#include "look_at_options.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/render_stack.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/sprite/sprite_renderer.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "terrasprite/warp/warp.h"
#include "viewer/viewer.h"

namespace terrasprite::cli {
namespace {

struct ViewOpts {
  TerrainOptions terrain;
  std::string size = "1280x720";
  std::string script, stats, record, play;
  viewer::ViewerOptions viewer;
  bool lighting = false, free = false;
  bool sync_keyframes = false;  ///< sprite: keyframes drawn in the frame (no second thread)
  LookAtOptions look;
  std::optional<int> lod_quads;  ///< unset: auto_lod_quads
};

/// One --mode's renderer stack, built on the viewer's render thread. The
/// voxel mode runs the ray caster at the panel's pixel-to-voxel ratio,
/// optionally every n-th frame real and the others warped, over pyramids
/// built once per run and shared by every stack the panel's settings create.
class StackRenderer : public viewer::ViewRenderer {
 public:
  StackRenderer(const Terrain& t, const RenderStackOptions& o)
      : stack_(make_render_stack(t, o)), sprite_(dynamic_cast<SpriteRenderer*>(stack_.real.get())) {
    if (o.mode == RenderMode::kVoxel)
      stack_.device = fmt::format(
          "cpu voxel {}, ratio {:.2f}{}",
          to_string(static_cast<VoxelRenderer&>(*stack_.real).options().variant), o.voxel_ratio,
          o.warp ? fmt::format(", {} warp, real every {}", to_string(*o.warp), o.real_every)
                 : std::string());
  }
  Renderer& renderer() override { return stack_.renderer(); }
  std::string device() const override { return stack_.device; }
  double error_px() const override {
    return sprite_ ? sprite_->last_error().value(sprite_->options().metric) : -1;
  }
  bool landed_keyframe() const override { return sprite_ && sprite_->last_landed(); }
  std::optional<AsyncKeyframeStats> keyframe_stats() const override {
    if (!sprite_ || !sprite_->async()) return std::nullopt;
    return sprite_->async_stats();
  }

 private:
  RenderStack stack_;
  SpriteRenderer* sprite_;
};

/// The stack options of the panel's settings `s`: GL modes draw in `context`
/// (may be null), voxel over the shared `pyramid`.
RenderStackOptions stack_options(const viewer::LiveSettings& s, int w, int h, bool lighting,
                                 bool async_keyframes, GlContext* context,
                                 const VoxelTerrain* pyramid) {
  RenderStackOptions o;
  o.mode = s.mode;
  o.width = w;
  o.height = h;
  if (s.mode == RenderMode::kVoxel) {
    o.voxel_ratio = s.voxel_ratio;
    o.voxels = pyramid;
    if (s.warp != "none") o.warp = parse_warp_method(s.warp);
    o.real_every = std::max(1, s.real_every);
    return o;
  }
  o.lod_quads = s.lod_quads;
  o.lighting = lighting;
  o.sprite_threshold_px = s.threshold_px;
  o.context = context;
  o.async_keyframes = async_keyframes;
  return o;
}

/// The first view: from half the extent south, a tenth of the extent above the
/// highest point, looking north at the terrain centre's lowest level; the
/// extent scaled as the overview path scales it (closer over flat terrain).
Camera start_camera(const Heightfield& h, double aspect) {
  const double e = h.extent() * overview_scale(h);
  Camera c = Camera::look_at({0, -0.5 * e, h.max_height() + 0.1 * e}, {0, 0, h.min_height()}, 60.0,
                             aspect);
  fit_clip_planes(c, h);
  return c;
}

/// --look-at's view, or the default first view.
Camera first_camera(const LookAtOptions& look, const Heightfield& h, double aspect) {
  if (const std::optional<LookAtView> v = parse_look_at(look, h))
    return look_at_camera(*v, h, aspect);
  return start_camera(h, aspect);
}

void run(ViewOpts& o, const OutputPolicy& policy) {
  auto [w, h] = parse_size(o.size, "--size");
  viewer::ViewerOptions& v = o.viewer;
  v.width = w;
  v.height = h;
  v.fly.bounded = !o.free;
  if (v.frames < 0) throw InputError(fmt::format("--frames {}: must be at least 0", v.frames));
  if (!(v.settings.voxel_ratio > 0 && v.settings.voxel_ratio <= 64))
    throw InputError(
        fmt::format("--voxel-ratio {}: must be within (0, 64]", v.settings.voxel_ratio));
  if (v.settings.real_every < 1 || v.settings.real_every > 64)
    throw InputError(fmt::format("--real-every {}: must be within 1..64", v.settings.real_every));
  if (!(v.record_every_s > 0 && v.record_every_s <= 3600))
    throw InputError(
        fmt::format("--record-every {:g}: must be in (0, 3600] seconds", v.record_every_s));
  if (!(v.fly.speed_mps >= 0 && v.fly.speed_mps <= viewer::kMaxSpeedMps))
    throw InputError(fmt::format("--speed {:g}: must be in [0, {:g}] m/s (0: the default)",
                                 v.fly.speed_mps, viewer::kMaxSpeedMps));
  if (v.fly.speed_mps > 0 && v.fly.speed_mps < viewer::kMinSpeedMps)
    throw InputError(fmt::format("--speed {:g}: must be at least {:g} m/s (0: the default)",
                                 v.fly.speed_mps, viewer::kMinSpeedMps));
  if (!(v.fly.clearance_m >= 0 && v.fly.clearance_m <= viewer::kMaxClearanceM))
    throw InputError(fmt::format("--clearance {:g}: must be in [0, {:g}] m (0: the default)",
                                 v.fly.clearance_m, viewer::kMaxClearanceM));
  if (!o.script.empty()) {
    v.script = viewer::load_input_script(o.script);
    v.scripted = true;
  }
  // Every file the run writes is checked before the terrain loads and the window opens.
  v.output = policy;
  v.record = o.record;
  viewer::check_view_outputs(v);
  if (!o.stats.empty()) check_output_file(o.stats, policy);
  Terrain terrain = load_terrain_verbose(o.terrain);
  v.settings.lod_quads = o.lod_quads.value_or(auto_lod_quads(terrain.heights));
  if (!o.play.empty()) load_path_file(o.play, terrain.heights, 2, double(w) / h);  // validate
  v.play = o.play;
  const bool lighting = o.lighting, async_keyframes = !o.sync_keyframes;
  viewer::RunStats stats = viewer::run_viewer(
      terrain.heights, first_camera(o.look, terrain.heights, double(w) / h), v,
      [&terrain, w, h, lighting, async_keyframes, pyramid = std::shared_ptr<VoxelTerrain>()](
          const viewer::LiveSettings& s,
          GlContext* context) mutable -> std::unique_ptr<viewer::ViewRenderer> {
        if (s.mode == RenderMode::kVoxel && !pyramid)
          pyramid = std::make_shared<VoxelTerrain>(terrain);
        return std::make_unique<StackRenderer>(
            terrain, stack_options(s, w, h, lighting, async_keyframes, context, pyramid.get()));
      });
  nlohmann::json j = viewer::stats_json(stats);
  if (!o.stats.empty()) report::write_json(j, o.stats, policy);
  fmt::print("view {}: {} frames, median {:.1f} fps, 1% low {:.1f} fps, latency p95 {:.0f} ms\n",
             to_string(stats.mode), stats.frames, double(j["fps_median"]),
             double(j["fps_low_1pct"]), double(j["latency_ms_p95"]));
}

}  // namespace

void add_view(CLI::App& app, const OutputPolicy& policy) {
  auto* cmd = app.add_subcommand(
      "view", "fly the terrain in a window (F1: keys); --script for measured, scripted runs");
  auto o = std::make_shared<ViewOpts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option_function<std::string>(
         "--mode", [o](const std::string& m) { o->viewer.settings.mode = parse_render_mode(m); },
         "renderer, switchable live (default sprite)")
      ->check(CLI::IsMember(render_mode_names()));
  cmd->add_option("--size", o->size, "window and render size WxH (default 1280x720)");
  cmd->add_option("--lod-quads", o->lod_quads,
                  "coarse grid quads (default: from the terrain, a quad of about 32 samples or "
                  "1 km, at least 16)");
  cmd->add_option("--threshold", o->viewer.settings.threshold_px,
                  "LOD-sprite keyframe threshold, pixels (default 1)");
  cmd->add_option("--voxel-ratio", o->viewer.settings.voxel_ratio,
                  "voxel: pixel-to-voxel ratio, > 0 (default 1; larger is faster and blurrier)");
  cmd->add_option("--warp", o->viewer.settings.warp,
                  "voxel: warp the frames between real ones: none, poly2 or depth (default none)")
      ->check(CLI::IsMember({"none", "poly2", "depth"}));
  cmd->add_option("--real-every", o->viewer.settings.real_every,
                  "voxel with --warp: every n-th frame real, 1..64 (default 4)");
  cmd->add_flag("--lighting", o->lighting, "simple sun lighting on top of the texture");
  cmd->add_flag("--sync-keyframes", o->sync_keyframes,
                "sprite: draw keyframes inside the frame, which then waits for them (default: on "
                "a second thread, for the camera predicted for when they land)");
  cmd->add_option("--script", o->script,
                  "replay timed input events from this JSON file (ends 1 s after the last)");
  cmd->add_option("--stats", o->stats, "write frame-rate and latency statistics JSON here");
  cmd->add_option("--frames", o->viewer.frames, "end after this many displayed frames");
  cmd->add_option("--record", o->record, "record the flight into this path JSON file");
  cmd->add_option("--record-every", o->viewer.record_every_s,
                  "seconds between recorded keyframes (default 0.5)");
  cmd->add_option("--play", o->play, "fly this path JSON file in real time");
  cmd->add_option(
      "--speed", o->viewer.fly.speed_mps,
      "flying speed m/s (default: half the height above ground per second, 5 m/s to 2% of "
      "the extent per second; +/- scale it)");
  cmd->add_option("--clearance", o->viewer.fly.clearance_m,
                  "minimum height above ground, metres (default 0.5% of the extent)");
  cmd->add_flag("--free", o->free, "allow flying far outside the terrain");
  add_look_at_options(*cmd, o->look);
  add_show_voids_option(*cmd, o->terrain);
  cmd->add_flag("--shared-context", o->viewer.share_context,
                "GL renderers draw in a context shared with the window, nothing read back "
                "(default off: on llvmpipe the window then waits for the renderer)");
  cmd->add_option("--screenshot-dir", o->viewer.screenshot_dir,
                  "where F2 screenshots and F5 recordings go (default .)");
  cmd->callback([o, &policy] { run(*o, policy); });
}

}  // namespace terrasprite::cli
