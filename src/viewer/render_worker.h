// SPDX-License-Identifier: MIT
// Renderer work off the event thread: a worker thread owns the renderer, draws
// the newest camera it was given, and hands back the newest finished frame.
// The event loop never waits for a frame, so an expensive one (a keyframe, a
// voxel frame) cannot stall input: the window keeps showing the last good
// frame meanwhile.
//
// GL renderers draw on the worker's context, which shares objects with the
// window's, into one of three colour + depth targets: one on screen, one
// finished and waiting to be shown, one being drawn. The window samples the
// finished target's texture; nothing is read back. CPU renderers (voxel)
// hand back their colour image.
#pragma once
#include <array>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "terrasprite/camera/camera.h"
#include "terrasprite/camera/frame.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/common/image.h"
#include "terrasprite/camera/renderer.h"
#include "terrasprite/experiment/render_mode.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite::viewer {

/// What the panel can change live.
struct LiveSettings {
  RenderMode mode = RenderMode::kSprite;
  double threshold_px = 1.0;  ///< LOD-sprite keyframe threshold
  int lod_quads = 16;           ///< coarse grid of lod and sprite
  double voxel_ratio = 1.0;     ///< voxel: pixel-to-voxel ratio of the multires traversal
  std::string warp = "none";    ///< voxel: none | poly2 | depth (frames between real ones warped)
  int real_every = 4;           ///< voxel with a warp: every n-th frame rendered for real
  bool operator==(const LiveSettings&) const = default;
};

/// The displayed frame against full resolution at the same camera (the
/// panel's "compare"): figures and the amplified difference image.
struct Comparison {
  double psnr = 0, ssim = 0, flip = 0;
  RenderMode mode = RenderMode::kFull;  ///< the renderer compared
  Image difference;  ///< |full - frame| x 4 per channel, rows top-down
};

/// A renderer with everything it owns (scene, voxel pyramids), built, used
/// and destroyed on the worker thread.
class ViewRenderer {
 public:
  virtual ~ViewRenderer() = default;
  virtual Renderer& renderer() = 0;
  virtual std::string device() const = 0;
  /// The LOD-sprite error of the last frame against its keyframe (pixels), or -1.
  virtual double error_px() const { return -1; }
  /// Whether the last frame took a keyframe that a second thread finished
  /// (LOD-sprite with asynchronous keyframes).
  virtual bool landed_keyframe() const { return false; }
  /// The keyframe worker's figures so far (LOD-sprite with asynchronous
  /// keyframes), else none.
  virtual std::optional<AsyncKeyframeStats> keyframe_stats() const { return std::nullopt; }
};
/// Builds the renderer for `settings`; `context` is the worker's GL context
/// (current on the calling thread; null when there is none), for GL renderers.
using ViewRendererFactory =
    std::function<std::unique_ptr<ViewRenderer>(const LiveSettings&, GlContext* context)>;
/// Makes the worker's GL context (sharing objects with the window's) current on
/// the calling thread and wraps it; called once, on the worker thread.
using ContextFactory = std::function<std::unique_ptr<GlContext>()>;

struct RenderedFrame {
  Frame frame;                   ///< timings, class, camera; colour only from CPU renderers
  unsigned texture = 0;          ///< the GL texture holding the frame (rows bottom-up), or 0
  std::uint64_t generation = 0;  ///< the input generation its camera included
  double error_px = -1;
  bool landed = false;                          ///< it took a keyframe finished on another thread
  std::optional<AsyncKeyframeStats> keyframes;  ///< the keyframe worker's figures, when one runs
  std::string device;
  LiveSettings settings;
  int slot = -1;
  std::optional<Comparison> comparison;  ///< when a compare was asked for
};

class RenderWorker {
 public:
  /// `context` may be empty: GL renderers then draw with their own contexts
  /// and hand back read-back colour like CPU renderers.
  RenderWorker(ViewRendererFactory factory, ContextFactory context);
  ~RenderWorker();  ///< stops after the frame in progress; GL objects die on its thread
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  /// The camera (with the input generation it includes) and settings to render
  /// next; replaces an older request. The worker renders continuously, each
  /// frame once the one before it was taken (none drawn only to be dropped).
  void request(const Camera& camera, std::uint64_t generation, const LiveSettings& settings);
  /// The newest frame finished since the last take(), if any; its texture
  /// stays untouched until the next take() returns a frame. Rethrows an
  /// exception the factory or renderer threw (InputError, DeviceError).
  std::optional<RenderedFrame> take();
  /// Waits up to `timeout_s` for a frame take() would return.
  void wait(double timeout_s);
  /// Compares the next frame with full resolution (a "full" renderer built
  /// by the factory on first use); the frame carries the Comparison.
  void request_compare();
  /// True while the worker builds a renderer (start, mode switch).
  bool building() const;

 private:
  struct Targets;
  void loop();
  RenderedFrame draw(ViewRenderer& r, const Camera& camera, Targets* targets);
  Comparison compare(ViewRenderer& r, RenderedFrame& shown, const Camera& camera,
                     std::unique_ptr<ViewRenderer>& reference, GlContext* context);

  ViewRendererFactory factory_;
  ContextFactory context_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false, has_request_ = false, building_ = false, compare_ = false;
  Camera camera_;
  std::uint64_t generation_ = 0;
  LiveSettings settings_;
  std::optional<RenderedFrame> done_;
  int shown_slot_ = -1;  // the target on screen (not to be drawn into)
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace terrasprite::viewer
