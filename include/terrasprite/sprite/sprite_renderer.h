// SPDX-License-Identifier: MIT
// The LOD-sprite renderer (Chen, Swan, Kuo, Kaufman, IEEE Visualization 1999):
// full-resolution keyframes rendered into textures, in-between frames drawn
// from a coarse grid projectively textured with the keyframe.
#pragma once
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "terrasprite/gl/gl_renderer.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/sprite/error_metric.h"

namespace terrasprite {

class GlContext;

/// Which cached keyframe makes room for a new one.
enum class CachePolicy {
  kLeastRecentlyUsed,  ///< the one that stopped being current longest ago
  kFarthest,           ///< the one whose camera is farthest from the current camera
};
/// "lru", "farthest".
const char* to_string(CachePolicy policy);

/// The coarse mesh sprite frames draw.
enum class CoarseMesh {
  kUniform,   ///< the paper's: a uniform grid of lod_quads x lod_quads quads
  kAdaptive,  ///< per keyframe, a screen-space-error quadtree for its camera (adaptive_mesh.h)
};
/// "uniform", "adaptive".
const char* to_string(CoarseMesh mesh);

struct SpriteOptions {
  int lod_quads = 16;  ///< coarse grid quads per side (>= 1)
  CoarseMesh mesh = CoarseMesh::kUniform;
  /// Adaptive mesh: at most this many triangles; 0 = the uniform grid's
  /// 2 x lod_quads^2, so both meshes (and plain LOD of lod_quads) draw the
  /// same budget. Otherwise >= 2.
  long long mesh_triangles = 0;
  /// Adaptive mesh: nodes whose screen-space error from the keyframe's
  /// camera is at most this many pixels stay whole (0 = spend the budget).
  double mesh_tolerance_px = 0;
  /// Keyframe when the metric's RMS error exceeds this (> 0): pixels for
  /// kPaper and kExact, grey levels (0-255) of predicted error for kContrast.
  double threshold_px = 1.0;
  /// Which variant triggers keyframes (paper and exact are always reported;
  /// kContrast reads each keyframe's colour back to weigh the exact error by
  /// its texture, SpriteError::contrast_levels; uniform mesh only). The
  /// paper's by default: per keyframe spent it is as good as exact
  /// reprojection or better, and at 1 px it keeps the paper's keyframe
  /// budget (docs/results/2026-12-07-lodsprite-paper-metric.md).
  ErrorMetric metric = ErrorMetric::kPaper;
  /// Second trigger: keyframe when more than this fraction of the in-view
  /// coarse-quad centres were not visible in the keyframe (so the view is
  /// mostly drawn with the fallback texture). 1 disables it.
  double max_fallback_fraction = 1.0;
  /// Third trigger: keyframe when SpriteError::resample_scale exceeds this
  /// (the keyframe's pixels stretched or shrunk by more than this factor on
  /// average); infinity disables it.
  double max_resample_scale = 1.25;
  /// The third trigger reads SpriteError::resample_aniso (the worst axis)
  /// instead of resample_scale (the area's mean).
  bool anisotropic_scale = false;
  /// Ours: the third trigger gives way where plain LOD would itself be far
  /// off. A keyframe magnified s times blurs each feature over about s - 1
  /// more pixels than a full-resolution frame; plain LOD of the same mesh
  /// misplaces it by SpriteError::drape_px pixels. So the keyframe may stretch
  /// to 1 + scale_per_drape_px x drape_px where that is above
  /// max_resample_scale (scale_trigger_limit). 0 = the constant trigger.
  /// 1/16 by default (docs/results/2026-12-01-lodsprite-scale-trigger.md).
  double scale_per_drape_px = 1.0 / 16;
  /// Ours: a coarse quad whose largest deviation from the full-resolution
  /// surface moves the current view's image by less than this many pixels
  /// (drape_is_sharp: the vertical deviation's component across the view
  /// ray, so none from straight above) takes the drape texture, as plain LOD would: there the
  /// coarse geometry is already right and the drape is sharper than a resampled keyframe. 0
  /// disables; so does the scene's rich shading (TerrainShading::kRich), under which the drape
  /// would pay the per-fragment shading the keyframe already paid.
  double sharp_px = 0.5;
  /// Ours: keyframes see past the view's edges by this fraction of its width
  /// (and height) on each side (a wider field of view and a larger image at
  /// the same pixels per degree), so quads entering the view after a
  /// keyframe are still in it instead of falling back to the drape texture.
  /// A keyframe's own frame is then its middle, composited. In [0, 0.5].
  double key_margin = 0;
  /// Ours: keyframes sample the view this many times more densely (linear;
  /// image size times this), so the camera can close in further before the
  /// scale trigger (max_resample_scale) fires, and sprite frames minify the
  /// keyframe instead of magnifying it. In [1, 2] (bilinear taps, no mipmaps).
  double key_supersample = 1;
  /// Keyframe cache: memory budget in bytes for all keyframes held (the
  /// current one and the cached ones, width x height x 8 bytes each: colour
  /// and depth). When a keyframe is due, a cached keyframe that no trigger
  /// rejects for the current view (the least error wins) becomes current
  /// instead of rendering a new one. Below two keyframes' worth the cache is off.
  std::size_t cache_bytes = 0;
  CachePolicy cache_policy = CachePolicy::kLeastRecentlyUsed;
  /// A cached keyframe is reused only while its error for the view is at most
  /// this fraction of threshold_px (and no other trigger fires): one reused at
  /// the edge of the threshold would serve fewer frames, and worse ones, than
  /// a fresh keyframe. In (0, 1].
  double cache_accept = 0.5;
  bool lighting = false;  ///< same sun as RasterOptions::lighting, on keyframes and fallback alike
  /// Asynchronous keyframes (the paper's second thread with viewpoint
  /// prediction): non-null = the context the renderer's is (or shares with),
  /// from which a second context is made for a worker thread that renders
  /// keyframes while draw() keeps drawing sprite frames from the newest
  /// finished one. Only the first keyframe (and forced ones) is drawn in
  /// draw()'s own frame. A keyframe is requested for the camera predicted
  /// (linear extrapolation of the last frames) for the frame it will land
  /// on, the keyframe latency in frames being measured as it goes. Must
  /// outlive the renderer. Not with the keyframe cache (cache_bytes > 0).
  const GlContext* async_context = nullptr;
  /// Async only: the first keyframe too comes from the worker. Until it
  /// lands, draw() draws the coarse mesh with the drape texture (frame class
  /// "lod"), so no frame ever waits for a full-resolution render (a viewer
  /// switching mode or threshold). Off: the first frame is a keyframe.
  bool async_first_keyframe = false;
  /// Async only: a keyframe is also requested when the error predicted for
  /// the view it would land on exceeds this fraction of threshold_px. At 1 a
  /// keyframe lands just as the old one reaches the threshold, slightly off
  /// its predicted camera, where the synchronous renderer shows an exact one.
  /// In (0, 1]; 0.6 by default (docs/results/2026-12-07-lodsprite-async-lead.md).
  double async_lead = 0.6;
};

/// What the asynchronous keyframes did since the renderer was made or reset().
struct AsyncKeyframeStats {
  long long requested = 0;  ///< keyframes asked of the worker
  long long landed = 0;     ///< finished and looked at by draw()
  long long used = 0;       ///< of those, made current
  /// Landed with an error over the trigger for the view of the frame it landed
  /// on (the prediction missed): still used when better than the current one,
  /// and a new one is requested at once.
  long long late = 0;
  long long late_used = 0;         ///< late ones used anyway
  double last_latency_frames = 0;  ///< displayed frames from request to landing, the last one
  double mean_latency_frames = 0;  ///< the same, mean over the landed ones
  double last_keyframe_ms = 0;     ///< the worker's wall time for the last one it finished, ms
  bool in_flight = false;          ///< a request is being rendered or waits to be taken
};

/// The third trigger's limit for a view: max(o.max_resample_scale,
/// 1 + o.scale_per_drape_px x e.drape_px) (SpriteOptions::scale_per_drape_px).
double scale_trigger_limit(const SpriteOptions& o, const SpriteError& e);

/// Why a keyframe was drawn.
enum class Trigger {
  kFirst,     ///< no keyframe yet
  kError,     ///< the metric's RMS error exceeded threshold_px
  kFallback,  ///< too many coarse-quad centres were not visible in the keyframe
  kScale,     ///< the keyframe's pixels were stretched or shrunk past max_resample_scale
  kForced,    ///< the caller asked for one (render_keyframe)
};
/// "first", "error", "fallback", "scale", "forced".
const char* to_string(Trigger trigger);

/// One width x height LOD-sprite renderer over `scene` (which must outlive it;
/// a current GlContext for its whole life). draw() measures the error of the
/// camera against the current keyframe and renders either a new keyframe
/// (class "key": the full-resolution mesh) or a sprite frame (class "sprite":
/// the coarse mesh, textured from the keyframe; coarse quads with a corner or
/// centre vertex hidden in the keyframe's depth buffer or outside its view,
/// and fragments outside the keyframe or on its sky, take the drape texture).
/// Frame::ms covers the metric, the drawing, and on keyframes the depth
/// read-back and visibility work that the technique needs. Throws InputError
/// naming `lod_quads` (< 1) or `threshold_px` (not > 0).
class SpriteRenderer : public GlRenderer {
 public:
  SpriteRenderer(Scene& scene, int width, int height, SpriteOptions options = {});
  ~SpriteRenderer() override;

  /// The automatic policy: keyframe on the first frame and whenever a
  /// trigger fires (trigger_for), else a sprite frame.
  Frame draw(const Camera& camera) override;
  /// A keyframe's colour is read from the keyframe texture (sky filled in).
  void read_back(Frame& frame, ReadBack what) override;
  std::string name() const override;

  /// Forced decisions (drawn, then read back), for figures and tests.
  /// render_sprite without a keyframe draws one (class "key") instead.
  Frame render_keyframe(const Camera& camera, ReadBack what = ReadBack::kColor);
  Frame render_sprite(const Camera& camera, ReadBack what = ReadBack::kColor);
  /// Makes `camera` the keyframe without reading anything back (for cheap
  /// simulations of the keyframe sequence: sweeps of thresholds and frame counts).
  void make_keyframe(const Camera& camera);

  /// Keyframe cache: keyframes held now besides the current one, the bytes
  /// all held keyframes take (never above SpriteOptions::cache_bytes when
  /// the cache is on), and whether the last draw() reused a cached keyframe.
  int cached_keyframes() const;
  std::size_t keyframe_bytes_held() const;
  bool last_cache_hit() const;

  /// Asynchronous keyframes (SpriteOptions::async_context): whether they are
  /// on, their counts so far, and whether the last draw() took a landed one.
  bool async() const;
  const AsyncKeyframeStats& async_stats() const;
  bool last_landed() const;
  /// The current keyframe's camera (undefined without one) and a number that
  /// changes whenever the current keyframe does (to replay which keyframe
  /// each frame was drawn from).
  /// Waits until the asynchronous keyframe in flight, if any, has landed (the
  /// next draw() takes it): makes a run independent of the worker's speed,
  /// for tests and for pausing. No-op without async keyframes.
  void wait_for_keyframe();
  const Camera& keyframe_camera() const;
  long long keyframe_serial() const;

  /// Forgets the keyframe, empties the cache, drops an asynchronous keyframe
  /// in flight and zeroes async_stats(): the next draw() is a keyframe (e.g.
  /// after a warm-up).
  void reset();
  bool has_keyframe() const;
  /// Error of `camera` against the current keyframe (zero without one).
  SpriteError error(const Camera& camera) const;
  /// The trigger `e` fires under the options (error before fallback before
  /// scale), or none: the one place a keyframe decision is made.
  std::optional<Trigger> trigger_for(const SpriteError& e) const;
  /// Whether `e` asks for a new keyframe under the options.
  bool keyframe_due(const SpriteError& e) const { return trigger_for(e).has_value(); }
  /// The error measured by the last draw() (both variants; zero on the first keyframe).
  const SpriteError& last_error() const;
  /// CPU time (ms) the last draw() spent deciding: the error metric against
  /// the keyframe, and against cached keyframes when one was due (inside Frame::ms).
  double last_decision_ms() const;
  /// Why the last draw drew a keyframe; none for a sprite frame.
  std::optional<Trigger> last_trigger() const;
  const SpriteOptions& options() const;
  /// The coarse mesh sprite frames draw now: the current keyframe's (its own
  /// with the adaptive mesh), or the uniform grid before any keyframe.
  const CoarseGrid& grid() const;
  /// The adaptive mesh's triangle budget (0 with the uniform mesh).
  long long mesh_budget() const;
  /// Per coarse quad of the current keyframe: 1 = drawn with the drape texture.
  const std::vector<std::uint8_t>& fallback_quads() const;

 private:
  enum class Decision { kAuto, kKeyframe, kSprite };
  Frame draw_as(const Camera& camera, Decision decision);
  void draw_sprite_pass(const Camera& camera);
  SpriteError land_and_request(const Camera& camera, SpriteError e);
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace terrasprite
