// SPDX-License-Identifier: MIT
#include "viewer/render_worker.h"

#include <chrono>
#include <utility>

namespace terrasprite::viewer {

RenderWorker::RenderWorker(ViewRendererFactory factory) : factory_(std::move(factory)) {
  thread_ = std::thread([this] { loop(); });
}

RenderWorker::~RenderWorker() {
  {
    std::lock_guard lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void RenderWorker::request(const Camera& camera, std::uint64_t generation,
                           const LiveSettings& settings) {
  {
    std::lock_guard lock(m_);
    camera_ = camera;
    generation_ = generation;
    settings_ = settings;
    has_request_ = true;
  }
  cv_.notify_all();
}

std::optional<RenderedFrame> RenderWorker::take() {
  std::lock_guard lock(m_);
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  return std::exchange(done_, std::nullopt);
}

void RenderWorker::wait(double timeout_s) {
  std::unique_lock lock(m_);
  cv_.wait_for(lock, std::chrono::duration<double>(timeout_s),
               [&] { return done_.has_value() || error_ || stop_; });
}

bool RenderWorker::building() const {
  std::lock_guard lock(m_);
  return building_;
}

void RenderWorker::loop() {
  std::unique_ptr<ViewRenderer> renderer;
  LiveSettings built;
  try {
    for (;;) {
      Camera camera;
      std::uint64_t generation = 0;
      LiveSettings settings;
      {
        std::unique_lock lock(m_);
        cv_.wait(lock, [&] { return stop_ || has_request_; });
        if (stop_) break;
        camera = camera_;
        generation = generation_;
        settings = settings_;
        building_ = !renderer || !(settings == built);
      }
      if (!renderer || !(settings == built)) {
        renderer.reset();  // one renderer (and GL context) at a time
        renderer = factory_(settings);
        built = settings;
        std::lock_guard lock(m_);
        building_ = false;
      }
      RenderedFrame r;
      r.frame = renderer->render(camera);
      r.generation = generation;
      r.error_px = renderer->error_px();
      r.device = renderer->device();
      r.settings = settings;
      {
        std::lock_guard lock(m_);
        done_ = std::move(r);
      }
      cv_.notify_all();
    }
  } catch (...) {
    std::lock_guard lock(m_);
    error_ = std::current_exception();
    building_ = false;
  }
  cv_.notify_all();
  renderer.reset();  // GL objects die on the thread whose context they belong to
}

}  // namespace terrasprite::viewer
