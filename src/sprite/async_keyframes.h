// SPDX-License-Identifier: MIT
// LOD-sprite keyframes rendered on a second thread (the future work of Chen
// et al. 1999, section 5): a worker with its own GL context, sharing textures
// with the caller's, renders each requested keyframe into a texture pair the
// caller's sprite frames then sample. GL fences order the two contexts.
#pragma once
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "sprite/keyframe.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {

/// One worker thread and a pool of keyframes (colour + depth textures, its
/// framebuffer and the CPU-side visibility), at most one request in flight.
/// All methods are called on one thread (the caller's), with the context the
/// worker's shares with current. The worker owns the keyframes' GL objects
/// (framebuffers are not shared between contexts) and frees them in its own
/// context; the caller only samples their textures.
///
/// Handover: the worker renders, reads the depth back (which drains its
/// pipeline), places a fence and flushes; take() makes the caller's context
/// wait on that fence (glWaitSync) before any later command samples the
/// textures. give_back() places a fence in the caller's context, which the
/// worker waits on before it renders into those textures again.
class AsyncKeyframes {
 public:
  /// Creates the shared context from `share` (which must outlive this), starts
  /// the worker and waits until its GL side (its own copy of the terrain's
  /// drape and full-resolution mesh: VAOs are not shared) is ready. Throws
  /// DeviceError when the shared context cannot be made or used. `terrain`
  /// must outlive this; `make_grid` gives each keyframe its coarse mesh for its
  /// camera (called on the worker thread).
  using GridMaker = std::function<std::shared_ptr<const CoarseGrid>(const Camera&)>;
  AsyncKeyframes(const GlContext& share, const Terrain& terrain, GridMaker make_grid, int width,
                 int height, bool lighting, bool contrast, TerrainShading shading,
                 KeyframeFraming framing = {});
  /// Stops the worker: a keyframe being rendered is finished first (GL has no
  /// way to abandon a draw), then the worker frees its GL objects and context.
  ~AsyncKeyframes();
  AsyncKeyframes(const AsyncKeyframes&) = delete;
  AsyncKeyframes& operator=(const AsyncKeyframes&) = delete;

  /// Whether a request is being rendered or has landed and not been taken.
  bool busy() const;
  /// Asks for a keyframe of `camera`. Only while !busy().
  void request(const Camera& camera);
  /// The requested keyframe once it has landed (the caller's context then
  /// waits on its fence before sampling it), else null without waiting. The
  /// caller holds it until give_back().
  const Keyframe* take();
  /// The same, waiting for the request in flight (null when there is none).
  const Keyframe* wait();
  /// Waits until no request is being rendered or pending (without taking it).
  void wait_landed();
  /// The caller is done sampling `key` (from take()); the worker may render into it again.
  void give_back(const Keyframe* key);
  /// Forgets the request in flight: what it renders is discarded on landing.
  void cancel();
  /// Keyframes the worker finished (taken or discarded).
  long long finished() const;
  /// Wall time the worker spent rendering the last keyframe it finished
  /// (capture and depth read-back; sharing the cores with the caller), ms; 0 before the first.
  double last_render_ms() const;

 private:
  struct Slot;
  void run(std::unique_ptr<GlContext> context, const Terrain& terrain);
  void render(Slot& slot, const Camera& camera, TerrainGpu& terrain);
  const Keyframe* take_locked(std::unique_lock<std::mutex>& lock);

  const GridMaker make_grid_;
  const int width_, height_;
  const bool lighting_;
  const bool contrast_;
  const TerrainShading shading_;
  const KeyframeFraming framing_;  // the main scene's, for the worker's own scene  // keyframes
                                   // also measure their contrast (ErrorMetric::kContrast)
  mutable std::mutex mutex_;
  std::condition_variable wake_;  // worker: a request or stop; caller: ready or landed
  std::vector<std::unique_ptr<Slot>> slots_;
  std::optional<Camera> pending_;  // requested, not yet started
  bool rendering_ = false;
  bool discard_ = false;  // the request in flight was cancelled
  bool stop_ = false;
  bool started_ = false;
  std::exception_ptr start_error_;
  long long finished_ = 0;
  double last_render_ms_ = 0;
  std::thread worker_;
};

}  // namespace terrasprite
