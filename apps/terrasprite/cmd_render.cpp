// SPDX-License-Identifier: MIT
// terrasprite render: one renderer along a path -> PNG frames + stats JSON.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <tuple>

#include "cli_common.h"
#include "commands.h"
#include "look_at_options.h"
#include "objects_options.h"
#include "render_modes.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/common/process_memory.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/experiment/render_run.h"
#include "terrasprite/experiment/render_stack.h"
#include "terrasprite/experiment/warp.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/output/output_file.h"
#include "terrasprite/output/video_writer.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::cli {
namespace {

struct RenderOpts {
  TerrainOptions terrain;
  std::string mode = "full";
  std::optional<int> lod_quads;  // unset: auto_lod_quads
  std::string mesh = "uniform";  // --mode sprite: its coarse mesh
  long long mesh_triangles = 0;
  std::string path = "overview";
  int frames = 460;
  double duration_s = 0;  // > 0: frames = duration x --fps instead of --frames
  std::string size = "512x512";
  std::string out;
  bool depth = false;
  bool lighting = false;
  std::string json;
  std::string warp;  // empty: every frame real
  int real_every = 4;
  double warp_margin = 0.05;
  // Video and frame range
  std::string video;
  VideoOptions video_opts;
  bool frames_png = false;
  bool no_images = false;
  std::string frame_range;
  // Memory along the run (a soak's curve)
  int memory_every = 100;
  std::string heap_trim = "on";
  ObjectsOptions objects;
  LookAtOptions look;
};

// The soak's figures: RSS every `every` frames, its peak, and the growth a
// long run is judged by (least squares over the frames after the first 1,000,
// once the renderers' caches and the allocator have settled).
nlohmann::json memory_json(const RenderRunResult& r, int every, bool trim) {
  const MemoryCurve& m = r.memory;
  nlohmann::json samples = nlohmann::json::array();
  for (auto [frame, mb] : m.samples) samples.push_back({frame, mb});
  return {{"sample_every", every},
          {"heap_trim", trim},
          {"trim_ms", m.trim_ms},
          {"peak_rss_mb", r.peak_rss_mb},
          {"rss_mb_end", m.samples.back().second},
          {"growth_mb_per_10k_frames_after_1000", m.growth_per_10k(1000)},
          {"rss_mb", samples}};
}

/// "A:B" -> [A, B) within [0, frames]; empty text: the whole run.
std::pair<int, int> parse_frame_range(const std::string& text, int frames) {
  if (text.empty()) return {0, frames};
  long long a = 0, b = 0;
  char colon = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%lld%c%lld%c", &a, &colon, &b, &extra) != 3 || colon != ':')
    throw InputError(fmt::format("--frame-range {}: expected A:B (frames A to B-1)", text));
  // Compared as 64-bit numbers, so a value past int's range is refused, never wrapped.
  if (a < 0 || b <= a || b > frames)
    throw InputError(
        fmt::format("--frame-range {}: need 0 <= A < B <= --frames ({})", text, frames));
  return {int(a), int(b)};
}

/// Refuses to replace a file the user did not ask us to replace (a video
/// terrasprite wrote carries its mark and may be replaced).
void check_video_target(const RenderOpts& o, const OutputPolicy& policy) {
  if (o.video.empty()) return;
  validate_video_options(o.video_opts);
  check_output_file(o.video, policy);
}

// Linear depth as 16-bit PNG: value = metres / m_per_unit, sky = 65535.
void save_depth(const Frame& f, double m_per_unit, const std::string& file) {
  std::vector<std::uint16_t> v(f.depth.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = std::isfinite(f.depth[i])
               ? std::uint16_t(std::clamp(std::lround(f.depth[i] / m_per_unit), 0L, 65534L))
               : 65535;
  save_png16(v, f.width(), f.height(), file);
}

// Everything checked before any output exists; throws InputError naming the option.
struct Checked {
  int w = 0, h = 0;
  int frames = 0;           ///< along the path: --frames, or --duration x --fps
  int first = 0, last = 0;  ///< the frames drawn, [first, last)
  RenderMode mode = RenderMode::kFull;
  std::optional<WarpMethod> warp;
  CoarseMesh mesh = CoarseMesh::kUniform;
  int lod_quads = 0;  ///< the coarse grid of the lod and sprite modes: --lod-quads, or chosen
};

// --frames, or --duration S at --fps N: S x N frames.
int frame_count(const RenderOpts& o) {
  int frames = o.frames;
  if (o.duration_s != 0) {
    if (!(o.duration_s > 0 && o.duration_s <= 1e5))
      throw InputError(fmt::format(
          "--duration {}: must be a number of seconds, above 0 and at most 100000", o.duration_s));
    if (!(o.video_opts.fps > 0 && o.video_opts.fps <= 1000))
      throw InputError(fmt::format("--fps {}: must be above 0 and at most 1000", o.video_opts.fps));
    frames = int(std::lround(o.duration_s * o.video_opts.fps));
  }
  if (frames < 1 || frames > 1000000)
    throw InputError(o.duration_s != 0
                         ? fmt::format("--duration {} at --fps {}: {} frames, must be between 1 "
                                       "and 1000000",
                                       o.duration_s, o.video_opts.fps, frames)
                         : fmt::format("--frames {}: must be between 1 and 1000000", frames));
  return frames;
}

// One line on stderr when the warped frames are too far from their real ones
// to warp cleanly (warp_stride's measure), with what to change.
void warn_warp_stride(const RenderOpts& o, const Checked& c, const std::vector<Camera>& path,
                      const Heightfield& ground) {
  if (!c.warp) return;
  const WarpStride s = warp_stride(path, o.real_every, ground);
  if (!s.too_far) return;
  fmt::print(stderr,
             "warning: --warp {}: between a real frame and its warped ones the camera turns up "
             "to {:.1f} deg (limit {:.0f}% of the {:.0f} deg field of view) and moves up to "
             "{:.0f}% of the depth at the image centre (limit {:.0f}%), worst at frame {}: expect "
             "streaks, bands and holes; use more --frames (or --duration S --fps N) or a lower "
             "--real-every\n",
             o.warp, s.max_turn_deg, 100 * kWarpMaxTurnOfFov, path.front().fov_y_deg,
             100 * s.max_move_over_depth, 100 * kWarpMaxMoveOverDepth, s.worst_frame);
}

// Where the stats JSON goes when neither --out nor --json names a place: beside
// the video (f.mp4 -> f.stats.json); empty otherwise.
std::string stats_beside_video(const RenderOpts& o) {
  if (!o.out.empty() || !o.json.empty() || o.video.empty()) return "";
  return std::filesystem::path(o.video).replace_extension(".stats.json").string();
}

Checked check_options(const RenderOpts& o, const OutputPolicy& policy) {
  if (o.out.empty() && o.video.empty())
    throw InputError("--out: an output directory is required (or --video FILE.mp4)");
  if (o.out.empty() && (o.frames_png || o.depth))
    throw InputError("--out: --frames-png and --depth need an output directory");
  Checked c;
  std::tie(c.w, c.h) = parse_size(o.size, "--size");
  c.frames = frame_count(o);
  std::tie(c.first, c.last) = parse_frame_range(o.frame_range, c.frames);
  c.mode = parse_render_mode(o.mode);
  check_outputs(policy, o.out, {o.json, stats_beside_video(o)});
  check_video_target(o, policy);
  return c;
}

// The options read once the terrain is loaded, in the order they are reported.
RenderStackOptions stack_options(const RenderOpts& o, Checked& c, const Heightfield& h) {
  if (!o.warp.empty()) c.warp = parse_warp_method(o.warp);
  if (o.real_every < 1)
    throw InputError(fmt::format("--real-every {}: must be at least 1", o.real_every));
  c.mesh = parse_mesh(o.mesh);
  check_mesh_triangles(o.mesh_triangles);
  if (!(o.warp_margin >= 0 && o.warp_margin <= 1))
    throw InputError(fmt::format("--warp-margin {}: must be within 0..1", o.warp_margin));
  RenderStackOptions so;
  so.mode = c.mode;
  so.width = c.w;
  so.height = c.h;
  so.lod_quads = c.lod_quads = o.lod_quads.value_or(auto_lod_quads(h));
  so.lighting = o.lighting;
  so.sprite_mesh = c.mesh;
  so.sprite_mesh_triangles = o.mesh_triangles;
  so.warp = c.warp;
  so.real_every = o.real_every;
  so.warp_margin = o.warp_margin;
  return so;
}

// Where the frames go: PNG frames, depth PNGs, the video.
struct FrameSinks {
  std::optional<OutputDir> out;
  std::optional<VideoWriter> video;
  bool png = false;
  double m_per_unit = 1;  ///< depth PNG units
};

void open_sinks(const RenderOpts& o, const Checked& c, const std::vector<Camera>& path,
                const OutputPolicy& policy, FrameSinks& s) {
  double far_max = 1.0;
  for (const Camera& cam : path) far_max = std::max(far_max, cam.far_m);
  s.m_per_unit = far_max / 65534.0;
  if (!o.out.empty()) s.out.emplace(o.out, policy);
  s.png = !o.no_images && (o.video.empty() || o.frames_png);
  if (!o.video.empty()) {
    s.video.emplace(o.video, c.w, c.h, o.video_opts);
    if (s.video->padded())
      fmt::print(stderr, "note: --video {}: {}x{} padded to {}x{} (H.264 4:2:0 needs even sizes)\n",
                 o.video, c.w, c.h, s.video->encoded_width(), s.video->encoded_height());
  }
}

// Flies frames [first, last) of the path into the sinks; the wall time
// includes finishing the video.
RenderRunResult fly_frames(const RenderOpts& o, const Checked& c, Renderer& renderer,
                           const std::vector<Camera>& path, FrameSinks& sinks, double& wall_ms) {
  RenderRunOptions ro;
  ro.first_frame = c.first;
  ro.read = o.depth ? ReadBack::kColorDepth : ReadBack::kColor;
  ro.memory_every = o.memory_every;
  ro.heap_trim = o.heap_trim == "on";
  ro.on_frame = [&](int i, const Frame& f) {
    if (sinks.png) save_png(f.color, sinks.out->file(fmt::format("frame_{:04d}.png", i)));
    if (o.depth)
      save_depth(f, sinks.m_per_unit, sinks.out->file(fmt::format("depth_{:04d}.png", i)));
    if (sinks.video) sinks.video->push(f.color);
  };
  Progress progress("render");
  ro.progress = std::ref(progress);
  const auto t0 = std::chrono::steady_clock::now();
  RenderRunResult r = run_render(renderer, std::span(path).subspan(c.first, c.last - c.first), ro);
  if (sinks.video) sinks.video->finish();
  wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

nlohmann::json stats_json(const RenderOpts& o, const Checked& c, const RenderStack& stack,
                          const Terrain& terrain, const RenderRunResult& run, double wall_ms,
                          const FrameSinks& sinks) {
  nlohmann::json frames = nlohmann::json::array();
  for (const RenderFrameRecord& s : run.frames)
    frames.push_back({{"frame", s.frame},
                      {"class", frame_class_name(s.cls)},
                      {"ms", s.ms},
                      {"gpu_ms", s.gpu_ms >= 0 ? nlohmann::json(s.gpu_ms) : nlohmann::json()},
                      {"triangles", s.triangles}});
  nlohmann::json j = {
      {"gl_renderer", stack.device},
      {"mode", to_string(c.mode)},
      {"warp", c.warp ? nlohmann::json(to_string(*c.warp)) : nlohmann::json(nullptr)},
      {"real_every", c.warp ? o.real_every : 1},
      {"warp_margin_px", {stack.margin_x, stack.margin_y}},
      {"size", {c.w, c.h}},
      {"lod_quads", c.lod_quads},
      {"terrain", terrain_json(terrain)},
      {"path", o.look.look_at.empty() ? o.path : "look-at " + o.look.look_at},
      {"median_ms", run.median_ms},
      {"wall_ms", wall_ms},
      {"frame_range", {c.first, c.last}},
      {"memory", memory_json(run, o.memory_every, o.heap_trim == "on")},
      {"frames", frames}};
  if (o.depth) j["depth_m_per_unit"] = sinks.m_per_unit;
  if (sinks.video)
    j["video"] = {{"file", o.video},
                  {"frames", sinks.video->frames()},
                  {"fps", o.video_opts.fps},
                  {"crf", o.video_opts.crf},
                  {"preset", o.video_opts.preset},
                  {"size", {sinks.video->encoded_width(), sinks.video->encoded_height()}},
                  {"padded", sinks.video->padded()}};
  return j;
}

// The cameras: --look-at's view (and an orbit of its target from there), or --path.
std::vector<Camera> flight_path(const RenderOpts& o, const Heightfield& h, int frames,
                                double aspect) {
  if (const std::optional<LookAtView> v = parse_look_at(o.look, h))
    return look_at_orbit(*v, h, frames, aspect);
  return make_path(o.path, h, frames, aspect);
}

void run(const RenderOpts& o, const OutputPolicy& policy) {
  Checked c = check_options(o, policy);
  Terrain terrain = load_terrain_verbose(o.terrain);
  std::vector<Camera> path = flight_path(o, terrain.heights, c.frames, double(c.w) / c.h);
  const RenderStackOptions so = stack_options(o, c, terrain.heights);
  warn_warp_stride(o, c, path, terrain.heights);
  RenderStack stack = make_render_stack(terrain, so);
  const std::unique_ptr<GlSceneObjects> objects =
      attach_objects(o.objects, terrain, stack.scene.get(), to_string(c.mode));
  if (c.mode == RenderMode::kSprite && c.first > 0)
    fmt::print(stderr, "note: --frame-range {}: LOD-sprite starts the range with a keyframe\n",
               o.frame_range);
  FrameSinks sinks;
  open_sinks(o, c, path, policy, sinks);
  double wall_ms = 0;
  const RenderRunResult run = fly_frames(o, c, stack.renderer(), path, sinks, wall_ms);
  const nlohmann::json j = stats_json(o, c, stack, terrain, run, wall_ms, sinks);
  if (sinks.out) {
    // JSON last: the directory is complete
    report::write_json(j, sinks.out->file("stats.json"), policy);
    sinks.out->commit();
  }
  if (!o.json.empty()) report::write_json(j, o.json, policy);
  const std::string beside = stats_beside_video(o);
  if (!beside.empty()) report::write_json(j, beside, policy);
  const bool coarse = c.mode == RenderMode::kLod || c.mode == RenderMode::kSprite;
  fmt::print("{}{}: {} frames {}x{} ({}), median {:.2f} ms/frame, {:.0f} ms in all on {} -> {}{}\n",
             o.mode, coarse ? fmt::format(" ({} x {} coarse quads)", c.lod_quads, c.lod_quads) : "",
             run.frames.size(), c.w, c.h, terrain.heights.name, run.median_ms, wall_ms,
             stack.device, sinks.out ? sinks.out->final_path().string() : o.video,
             beside.empty() ? "" : ", stats " + beside);
}

}  // namespace

void add_render(CLI::App& app, const OutputPolicy& policy) {
  auto* cmd = app.add_subcommand("render",
                                 "render a camera path with one renderer: PNG frames + stats JSON");
  auto o = std::make_shared<RenderOpts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option(
         "--mode", o->mode,
         fmt::format("renderer: {} (default {})", fmt::join(render_mode_names(), " | "), o->mode))
      ->check(CLI::IsMember(render_mode_names()));
  cmd->add_option("--lod-quads", o->lod_quads,
                  "coarse grid quads per side for lod modes (default: from the terrain, a quad of "
                  "about 32 samples or 1 km, at least 16; 16 is the paper setup)");
  cmd->add_option("--mesh", o->mesh,
                  "--mode sprite: coarse mesh, uniform (default, the --lod-quads grid) | adaptive "
                  "(per keyframe, a screen-space-error quadtree for its camera)");
  cmd->add_option("--mesh-triangles", o->mesh_triangles,
                  "--mesh adaptive: triangle budget (default 0 = the uniform grid's 2 x "
                  "lod-quads^2)");
  CLI::Option* path = add_path_option(*cmd, o->path);
  auto* frames = cmd->add_option("--frames", o->frames, "frames along the path (default 460)");
  cmd->add_option("--duration", o->duration_s,
                  "instead of --frames: seconds of flight at --fps frames a second (frames = "
                  "duration x fps)")
      ->excludes(frames);
  cmd->add_option("--size", o->size, "image size WxH (default 512x512)");
  // Checked in run(), so a parse error (e.g. an unknown option) is reported first.
  cmd->add_option("--out", o->out,
                  "output directory: PNG frames and stats.json (required unless --video)");
  cmd->add_flag("--depth", o->depth,
                "also write linear depth as 16-bit PNG (depth_m_per_unit in the JSON)");
  cmd->add_flag(
      "--lighting", o->lighting,
      "simple sun lighting on top of the texture (off: the derived texture is hillshaded)");
  cmd->add_option("--json", o->json,
                  "also write the stats JSON here (with --video and no --out or --json: beside "
                  "the video, FILE.stats.json)");
  cmd->add_option("--warp", o->warp,
                  "warp frames between real ones: poly2 (2D polynomial) or depth (3D reprojection)")
      ->check(CLI::IsMember({"poly2", "depth"}));
  cmd->add_option("--real-every", o->real_every,
                  "with --warp: render every K-th frame for real, warp the rest (default 4)");
  cmd->add_option("--warp-margin", o->warp_margin,
                  "with --warp: real frames drawn this fraction wider on each side (default 0.05)");
  cmd->add_option("--video", o->video,
                  "also write an H.264 MP4 (yuv420p, +faststart) through ffmpeg; PNG frames then "
                  "only with --frames-png");
  cmd->add_option("--fps", o->video_opts.fps,
                  "video frame rate, and the flight's with --duration (default 30)");
  cmd->add_option("--crf", o->video_opts.crf, "x264 constant rate factor 0..51 (default 18)");
  cmd->add_option("--preset", o->video_opts.preset, "x264 preset (default veryfast)");
  cmd->add_flag("--frames-png", o->frames_png, "with --video, keep writing PNG frames too");
  cmd->add_flag("--no-images", o->no_images, "write no PNG frames (stats only; for timing)");
  cmd->add_option("--frame-range", o->frame_range,
                  "render only frames A to B-1 of the --frames run (A:B), for splitting a long "
                  "run across machines");
  cmd->add_option("--memory-every", o->memory_every,
                  "sample resident memory every N frames into stats.json's memory curve "
                  "(default 100)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--heap-trim", o->heap_trim,
                  "on: at each memory sample hand freed heap pages back to the OS (default on)")
      ->check(CLI::IsMember({"on", "off"}));
  add_objects_options(*cmd, o->objects);
  add_look_at_options(*cmd, o->look)->excludes(path);
  add_show_voids_option(*cmd, o->terrain);
  cmd->callback([o, &policy] { run(*o, policy); });
}

}  // namespace terrasprite::cli
