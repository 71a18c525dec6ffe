// SPDX-License-Identifier: MIT
// The LOD-sprite policy (Chen, Swan, Kuo, Kaufman 1999): measure the error of
// the new view against the keyframe (Eq. 1-2); past the threshold render a new
// keyframe, otherwise a sprite frame from the coarse mesh.
#include "terrasprite/sprite/sprite_renderer.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "gl/frame_timer.h"
#include "sprite/async_keyframes.h"
#include "sprite/camera_prediction.h"
#include "sprite/keyframe.h"
#include "sprite/keyframe_cache.h"
#include "sprite/sprite_pass.h"
#include "terrasprite/common/error.h"
#include "terrasprite/sprite/adaptive_mesh.h"

namespace terrasprite {

const char* to_string(Trigger t) {
  switch (t) {
    case Trigger::kFirst:
      return "first";
    case Trigger::kError:
      return "error";
    case Trigger::kFallback:
      return "fallback";
    case Trigger::kScale:
      return "scale";
    case Trigger::kForced:
      return "forced";
  }
  return "?";
}

double scale_trigger_limit(const SpriteOptions& o, const SpriteError& e) {
  return std::max(o.max_resample_scale, 1.0 + o.scale_per_drape_px * e.drape_px);
}

const char* to_string(CoarseMesh m) {
  return m == CoarseMesh::kUniform ? "uniform" : "adaptive";
}

const char* to_string(CachePolicy p) {
  return p == CachePolicy::kLeastRecentlyUsed ? "lru" : "farthest";
}

// At most this fraction of the in-view coarse-quad centres may be missing
// from a reused cached keyframe.
constexpr double kCacheMaxFallback = 0.25;
// Asynchronous keyframes: how many frames ahead the first request looks,
// before any keyframe has landed to measure the latency.
constexpr double kInitialLatencyFrames = 8;

struct SpriteRenderer::State {
  Scene& scene;
  SpriteOptions options;
  std::shared_ptr<const CoarseGrid> uniform;     // the uniform grid (always made)
  std::unique_ptr<const AdaptiveMesher> mesher;  // with the adaptive mesh
  AdaptiveMeshOptions mesh_options;
  std::unique_ptr<GpuMesh> adaptive_gpu;  // the adaptive grid uploaded last
  std::uint64_t uploaded = 0;             // its serial
  int width, height;
  KeyframeFraming framing;
  std::unique_ptr<Keyframe> key;          // the keyframe drawn in this context (always allocated)
  std::unique_ptr<AsyncKeyframes> async;  // the keyframe worker, when on
  const Keyframe* held = nullptr;         // the worker's keyframe in use; null: `key` is current
  CameraPredictor predictor;
  AsyncKeyframeStats async_stats;
  long long requested_at = 0;  // tick of the request in flight
  double latency_frames = kInitialLatencyFrames;
  bool landed = false;   // the last draw took a landed keyframe
  long long serial = 0;  // changes with the current keyframe
  KeyframeCache cache;
  long long tick = 0;  // draws so far (the cache's clock)
  bool cache_hit = false;
  double decision_ms = 0;
  SpritePass pass;
  SpriteError last;
  std::optional<Trigger> trigger;
  bool last_was_key = false;
  std::vector<std::uint8_t> flags;  // this frame's per-quad drape flags

  State(Scene& s, int w, int h, const SpriteOptions& o)
      : scene(s),
        options(o),
        uniform(
            std::make_shared<const CoarseGrid>(make_coarse_grid(s.terrain().heights, o.lod_quads))),
        width(w),
        height(h),
        framing{o.key_margin, o.key_supersample},
        key(std::make_unique<Keyframe>(w, h, o.metric == ErrorMetric::kContrast, framing)),
        cache(cache_capacity(o, framing.width(w), framing.height(h)), o.cache_policy) {
    if (o.mesh == CoarseMesh::kAdaptive) {
      mesher = std::make_unique<const AdaptiveMesher>(s.terrain().heights);
      mesh_options.triangle_budget =
          o.mesh_triangles > 0 ? o.mesh_triangles : 2LL * o.lod_quads * o.lod_quads;
      mesh_options.tolerance_px = o.mesh_tolerance_px;
    }
  }

  /// The coarse mesh for a keyframe of `camera` (thread-safe).
  std::shared_ptr<const CoarseGrid> grid_for(const Camera& camera) const {
    if (!mesher) return uniform;
    return std::make_shared<const CoarseGrid>(mesher->build(framing.camera(camera, width, height),
                                                            framing.width(width),
                                                            framing.height(height), mesh_options));
  }
  const CoarseGrid& grid() const { return current().grid ? *current().grid : *uniform; }
  /// The GPU copy of the current keyframe's coarse mesh.
  const GpuMesh& coarse_gpu(TerrainGpu& terrain) {
    const CoarseGrid& g = grid();
    if (!g.adaptive) return terrain.mesh(options.lod_quads);
    if (uploaded != g.serial) {
      const Heightfield& h = terrain.terrain().heights;
      GridMesh cpu;
      cpu.vertices.reserve(g.mesh_vertices.size() * 6);
      for (const glm::dvec3& v : g.mesh_vertices) {
        const int i = int(std::lround(v.x / h.spacing_x + (h.width - 1) * 0.5));
        const int j = int(std::lround((h.height - 1) * 0.5 - v.y / h.spacing_y));
        const glm::dvec3 n = grid_normal(h, i, j);
        cpu.vertices.insert(cpu.vertices.end(), {float(v.x), float(v.y), float(v.z), float(n.x),
                                                 float(n.y), float(n.z)});
      }
      cpu.indices = g.triangles;
      adaptive_gpu = std::make_unique<GpuMesh>();
      upload_grid_mesh(*adaptive_gpu, cpu);
      uploaded = g.serial;
    }
    return *adaptive_gpu;
  }

  static std::size_t keyframe_bytes(int w, int h) { return std::size_t(w) * std::size_t(h) * 8; }
  static int cache_capacity(const SpriteOptions& o, int w, int h) {
    return int(std::max<std::size_t>(o.cache_bytes / keyframe_bytes(w, h), 1) - 1);
  }
  const Keyframe& current() const { return held ? *held : *key; }
  /// The worker's keyframe in use goes back to it (`key` is current again).
  void drop_held() {
    if (held) async->give_back(std::exchange(held, nullptr));
  }
  /// A keyframe to render into: the current one goes to the cache, and the
  /// cache's evicted one (or a new one) comes back.
  void retire_current(const Camera& now) {
    drop_held();
    ++serial;
    if (cache.capacity() == 0 || !key->valid) return;
    std::unique_ptr<Keyframe> spare = cache.put(std::move(key), tick, now);
    key = spare ? std::move(spare)
                : std::make_unique<Keyframe>(width, height,
                                             options.metric == ErrorMetric::kContrast, framing);
    key->valid = false;
  }
};

namespace {
const SpriteOptions& validated(const SpriteOptions& o) {
  if (o.lod_quads < 1)
    throw InputError(fmt::format("lod_quads {}: must be at least 1", o.lod_quads));
  if (o.async_context && o.cache_bytes > 0)
    throw InputError("async keyframes and the keyframe cache cannot be combined");
  if (!(o.cache_accept > 0 && o.cache_accept <= 1))
    throw InputError(fmt::format("cache_accept {}: must be in (0, 1]", o.cache_accept));
  if (!(o.async_lead > 0 && o.async_lead <= 1))
    throw InputError(fmt::format("async_lead {}: must be in (0, 1]", o.async_lead));
  if (o.mesh == CoarseMesh::kAdaptive && o.metric == ErrorMetric::kContrast)
    throw InputError(
        "the contrast metric needs the uniform mesh (its quads are measured on the grid)");
  if (!(o.key_margin >= 0 && o.key_margin <= 0.5))
    throw InputError(fmt::format("key_margin {}: must be in [0, 0.5]", o.key_margin));
  if (!(o.key_supersample >= 1 && o.key_supersample <= 2))
    throw InputError(fmt::format("key_supersample {}: must be in [1, 2]", o.key_supersample));
  if (o.metric == ErrorMetric::kContrast && (o.key_margin != 0 || o.key_supersample != 1))
    throw InputError(
        "the contrast metric needs keyframes framed as the view (no key margin or supersampling)");
  if (o.mesh_triangles != 0 && o.mesh_triangles < 2)
    throw InputError(fmt::format("mesh_triangles {}: must be 0 (the uniform grid's) or at least 2",
                                 o.mesh_triangles));
  if (!(o.mesh_tolerance_px >= 0))
    throw InputError(fmt::format("mesh_tolerance_px {}: must be at least 0", o.mesh_tolerance_px));
  if (!(o.scale_per_drape_px >= 0 && std::isfinite(o.scale_per_drape_px)))
    throw InputError(fmt::format("scale_per_drape_px {}: must be a finite number, at least 0",
                                 o.scale_per_drape_px));
  if (!(o.threshold_px > 0))
    throw InputError(
        fmt::format("threshold_px {}: must be a positive number of pixels", o.threshold_px));
  return o;
}
}  // namespace

SpriteRenderer::SpriteRenderer(Scene& scene, int width, int height, SpriteOptions options)
    : GlRenderer(width, height),
      s_(std::make_unique<State>(scene, width, height, validated(options))) {
  // Upload both meshes now, not inside the first timed frame.
  scene.prepare(0);
  scene.prepare(options.lod_quads);
  if (options.async_context)
    s_->async = std::make_unique<AsyncKeyframes>(
        *options.async_context, scene.terrain(),
        [s = s_.get()](const Camera& c) { return s->grid_for(c); }, width, height, options.lighting,
        options.metric == ErrorMetric::kContrast, scene.shading(), s_->framing);
}

SpriteRenderer::~SpriteRenderer() = default;

std::string SpriteRenderer::name() const {
  if (s_->mesher) return fmt::format("sprite-adaptive{}", s_->mesh_options.triangle_budget);
  return fmt::format("sprite{}", s_->options.lod_quads);
}
bool SpriteRenderer::has_keyframe() const {
  return s_->current().valid;
}
void SpriteRenderer::reset() {
  s_->drop_held();
  if (s_->async) s_->async->cancel();
  s_->predictor.clear();
  s_->async_stats = {};
  s_->latency_frames = kInitialLatencyFrames;
  s_->landed = false;
  s_->key->valid = false;
  s_->cache.clear();
  s_->cache_hit = false;
  s_->last = {};
  s_->trigger.reset();
}
const SpriteError& SpriteRenderer::last_error() const {
  return s_->last;
}
std::optional<Trigger> SpriteRenderer::last_trigger() const {
  return s_->trigger;
}
const SpriteOptions& SpriteRenderer::options() const {
  return s_->options;
}
const CoarseGrid& SpriteRenderer::grid() const {
  return s_->grid();
}
long long SpriteRenderer::mesh_budget() const {
  return s_->mesher ? s_->mesh_options.triangle_budget : 0;
}
const std::vector<std::uint8_t>& SpriteRenderer::fallback_quads() const {
  return s_->current().fallback;
}
bool SpriteRenderer::async() const {
  return s_->async != nullptr;
}
const AsyncKeyframeStats& SpriteRenderer::async_stats() const {
  return s_->async_stats;
}
bool SpriteRenderer::last_landed() const {
  return s_->landed;
}
void SpriteRenderer::wait_for_keyframe() {
  if (s_->async) s_->async->wait_landed();
}
const Camera& SpriteRenderer::keyframe_camera() const {
  return s_->current().camera;
}
long long SpriteRenderer::keyframe_serial() const {
  return s_->serial;
}

int SpriteRenderer::cached_keyframes() const {
  return s_->cache.size();
}
std::size_t SpriteRenderer::keyframe_bytes_held() const {
  return std::size_t(s_->cache.size() + 1) *
         State::keyframe_bytes(s_->framing.width(s_->width), s_->framing.height(s_->height));
}
double SpriteRenderer::last_decision_ms() const {
  return s_->decision_ms;
}
bool SpriteRenderer::last_cache_hit() const {
  return s_->cache_hit;
}

SpriteError SpriteRenderer::error(const Camera& camera) const {
  if (!s_->current().valid) return {};
  return sprite_error(*s_->current().grid, s_->current().samples, camera);
}

std::optional<Trigger> SpriteRenderer::trigger_for(const SpriteError& e) const {
  // Eq. (2): mean squared error over the samples > threshold^2.
  const SpriteOptions& o = s_->options;
  if (e.value(o.metric) > o.threshold_px) return Trigger::kError;
  if (e.fallback_fraction() > o.max_fallback_fraction) return Trigger::kFallback;
  if ((o.anisotropic_scale ? e.resample_aniso : e.resample_scale) > scale_trigger_limit(o, e))
    return Trigger::kScale;
  return std::nullopt;
}

void SpriteRenderer::make_keyframe(const Camera& camera) {
  s_->retire_current(camera);
  s_->key->capture(s_->scene.terrain_gpu(), s_->grid_for(camera), camera, s_->options.lighting);
}

void SpriteRenderer::draw_sprite_pass(const Camera& camera) {
  State& s = *s_;
  TerrainGpu& terrain = s.scene.terrain_gpu();
  const CoarseGrid& g = s.grid();
  s.flags = s.current().fallback;
  if (!s.current().valid)  // no keyframe yet (async first keyframe): all drape, plain LOD
    s.flags.assign(static_cast<std::size_t>(g.quad_count()), 1);
  if (s.options.sharp_px > 0 && s.scene.shading() == TerrainShading::kPlain) {
    // Quads whose coarse geometry is already right at this distance take the
    // drape texture. Not under rich shading: there the drape would pay the
    // per-fragment shading the keyframe has already paid.
    for (std::size_t q = 0; q < s.flags.size(); ++q)
      if (!s.flags[q] && drape_is_sharp(g, int(q), camera, height(), s.options.sharp_px))
        s.flags[q] = 1;
  }
  const GpuMesh& coarse = s.coarse_gpu(terrain);
  begin_output();
  s.pass.draw(terrain, coarse, g, s.current(), glm::mat4(gl::view_projection_reversed_z(camera)),
              s.flags, s.options.lighting);
}

Frame SpriteRenderer::draw_as(const Camera& camera, Decision d) {
  State& s = *s_;
  TerrainGpu& terrain = s.scene.terrain_gpu();
  timer().begin();
  ++s.tick;
  s.cache_hit = false;
  s.landed = false;
  const auto decision_start = std::chrono::steady_clock::now();
  if (s.async) s.predictor.observe(camera);
  SpriteError e = error(camera);
  const bool first_async = s.async && s.options.async_first_keyframe && d == Decision::kAuto;
  if (!has_keyframe() && !first_async) {
    e = {};
    s.trigger = Trigger::kFirst;
  } else if (d == Decision::kKeyframe) {
    s.trigger = Trigger::kForced;
  } else if (d == Decision::kAuto && s.async) {
    e = land_and_request(camera, e);
    s.trigger.reset();
  } else if (d == Decision::kAuto) {
    s.trigger = trigger_for(e);
    if (s.trigger && s.cache.size() > 0) {
      // A cached keyframe that no trigger rejects for this view, least error first.
      std::unique_ptr<Keyframe> hit = s.cache.take_best([&](const Keyframe& k) {
        const SpriteError ek = sprite_error(*k.grid, k.samples, camera);
        const double v = ek.value(s.options.metric);
        // A keyframe from elsewhere may see the view only in part: the
        // quads it lacks would take the drape texture, so few may be missing.
        const bool accept = !trigger_for(ek) &&
                            v <= s.options.cache_accept * s.options.threshold_px &&
                            ek.fallback_fraction() <= kCacheMaxFallback;
        return accept ? ek.fallback_fraction() + 0.01 * v : INFINITY;
      });
      if (hit) {
        s.cache.put(std::move(s.key), s.tick, camera);  // an evicted keyframe is freed
        s.key = std::move(hit);
        ++s.serial;
        s.cache_hit = true;
        s.trigger.reset();
        e = error(camera);
      }
    }
  } else {
    s.trigger.reset();
  }
  const bool key = s.trigger.has_value();
  s.decision_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - decision_start)
          .count();
  long long triangles = 0;
  if (key) {
    s.retire_current(camera);
    s.key->capture(terrain, s.grid_for(camera), camera, s.options.lighting);
    if (s.mesher) s.coarse_gpu(terrain);  // upload the new mesh inside the keyframe's frame
    // The keyframe textures are the frame; a caller's target, a frame with
    // objects over the terrain (keyframes hold terrain only) or a keyframe
    // framed wider than the view gets a copy.
    if (output().framebuffer != own_target().framebuffer() || s.scene.has_objects() ||
        !s.framing.identity()) {
      begin_output();
      s.pass.composite_keyframe(*s.key);
    }
    triangles = terrain.mesh(0).triangles;
  } else {
    // Before the first keyframe lands every quad takes the drape (a new
    // keyframe's fallback flags are all set): plain coarse LOD.
    draw_sprite_pass(camera);
    triangles = s.grid().triangle_count();
  }
  triangles += s.scene.draw_objects(camera);  // over the sprite, against its depth
  const gl::FrameTime t = timer().end();
  s.last = e;
  s.last_was_key = key;
  return make_frame(camera, t,
                    key              ? FrameClass::kKey
                    : has_keyframe() ? FrameClass::kSprite
                                     : FrameClass::kLod,
                    triangles);
}

void SpriteRenderer::read_back(Frame& f, ReadBack what) {
  State& s = *s_;
  if (!s.last_was_key || output().framebuffer != own_target().framebuffer() ||
      s.scene.has_objects() || !s.framing.identity()) {
    GlRenderer::read_back(f, what);
    return;
  }
  const gl::RenderTarget& t = s.key->target;
  read_framebuffer(t.framebuffer(), t.width(), t.height(), f.camera, f, what);
  if (has(what, ReadBack::kColor))
    for (std::size_t i = 0; i < f.color.rgba.size(); i += 4)  // keyframe sky is transparent black
      if (f.color.rgba[i + 3] == 0) {
        f.color.rgba[i] = kSkyColor[0];
        f.color.rgba[i + 1] = kSkyColor[1];
        f.color.rgba[i + 2] = kSkyColor[2];
        f.color.rgba[i + 3] = 255;
      }
}

// Asynchronous keyframes, once per automatic frame: take the keyframe that
// landed, if any (used when under the trigger for this view, or else when
// better than the current one), then ask for the next one when the current
// keyframe fails this view or the view predicted for when it would land.
SpriteError SpriteRenderer::land_and_request(const Camera& camera, SpriteError e) {
  State& s = *s_;
  AsyncKeyframeStats& st = s.async_stats;
  const ErrorMetric m = s.options.metric;
  if (const Keyframe* k = s.async->take()) {
    s.landed = true;
    ++st.landed;
    st.last_latency_frames = double(s.tick - s.requested_at);
    st.mean_latency_frames += (st.last_latency_frames - st.mean_latency_frames) / double(st.landed);
    s.latency_frames = st.last_latency_frames;
    st.last_keyframe_ms = s.async->last_render_ms();
    const SpriteError ek = sprite_error(*k->grid, k->samples, camera);
    const bool late = trigger_for(ek).has_value();
    st.late += late;
    if (!late || ek.value(m) < e.value(m) || !s.current().valid) {
      s.drop_held();
      s.held = k;
      ++s.serial;
      ++st.used;
      st.late_used += late;
      e = ek;
    } else {
      s.async->give_back(k);
    }
  }
  if (!s.async->busy()) {
    const Camera ahead = s.predictor.predict(s.latency_frames, s.scene.terrain().heights);
    const SpriteError at_landing = s.current().valid
                                       ? sprite_error(*s.current().grid, s.current().samples, ahead)
                                       : SpriteError{};
    if (!s.current().valid || trigger_for(e) || trigger_for(at_landing) ||
        at_landing.value(s.options.metric) > s.options.async_lead * s.options.threshold_px) {
      s.async->request(ahead);
      s.requested_at = s.tick;
      ++st.requested;
    }
  }
  st.in_flight = s.async->busy();
  return e;
}

Frame SpriteRenderer::draw(const Camera& camera) {
  return draw_as(camera, Decision::kAuto);
}
Frame SpriteRenderer::render_keyframe(const Camera& camera, ReadBack what) {
  Frame f = draw_as(camera, Decision::kKeyframe);
  if (what != ReadBack::kNone) read_back(f, what);
  return f;
}
Frame SpriteRenderer::render_sprite(const Camera& camera, ReadBack what) {
  Frame f = draw_as(camera, Decision::kSprite);
  if (what != ReadBack::kNone) read_back(f, what);
  return f;
}

}  // namespace terrasprite
