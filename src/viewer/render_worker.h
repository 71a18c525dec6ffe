// SPDX-License-Identifier: MIT
// Renderer work off the event thread: a worker thread owns the renderer (and
// its own GL context), renders the newest camera it was given, and hands back
// the newest finished frame. The event loop never waits for a frame, so an
// expensive one (a keyframe, a voxel frame) cannot stall input: the window
// keeps showing the last good frame meanwhile.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "terrasprite/camera.h"
#include "terrasprite/frame.h"

namespace terrasprite::viewer {

/// What the panel can change live.
struct LiveSettings {
  std::string mode = "sprite";  ///< full | lod | sprite | voxel
  double threshold_px = 1.0;    ///< LOD-sprite keyframe threshold
  int lod_quads = 16;           ///< coarse grid of lod and sprite
  bool operator==(const LiveSettings&) const = default;
};

/// A renderer with everything it owns (context, scene), built and used on the
/// worker thread only.
class ViewRenderer {
 public:
  virtual ~ViewRenderer() = default;
  virtual Frame render(const Camera& camera) = 0;
  virtual std::string device() const = 0;
  /// The LOD-sprite error of the last frame against its keyframe (pixels), or -1.
  virtual double error_px() const { return -1; }
};
using ViewRendererFactory = std::function<std::unique_ptr<ViewRenderer>(const LiveSettings&)>;

struct RenderedFrame {
  Frame frame;
  std::uint64_t generation = 0;  ///< the input generation its camera included
  double error_px = -1;
  std::string device;
  LiveSettings settings;
};

class RenderWorker {
 public:
  explicit RenderWorker(ViewRendererFactory factory);
  ~RenderWorker();  ///< stops after the frame in progress; the renderer dies on its thread
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  /// The camera (with the input generation it includes) and settings to render
  /// next; replaces an older request. The worker renders continuously.
  void request(const Camera& camera, std::uint64_t generation, const LiveSettings& settings);
  /// The newest frame finished since the last take(), if any. Rethrows an
  /// exception the factory or renderer threw (InputError, DeviceError).
  std::optional<RenderedFrame> take();
  /// Waits up to `timeout_s` for a frame take() would return.
  void wait(double timeout_s);
  /// True while the worker builds a renderer (start, mode switch).
  bool building() const;

 private:
  void loop();

  ViewRendererFactory factory_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false, has_request_ = false, building_ = false;
  Camera camera_;
  std::uint64_t generation_ = 0;
  LiveSettings settings_;
  std::optional<RenderedFrame> done_;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace terrasprite::viewer
