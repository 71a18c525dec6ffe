// SPDX-License-Identifier: MIT
// The keyframe worker: one thread, its own GL context sharing textures with
// the renderer's, a pool of keyframes, fences both ways (see the header).
#include "sprite/async_keyframes.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <utility>

#include "terrasprite/raster/scene.h"

namespace terrasprite {

// llvmpipe rasterizes the flushed batches of all contexts in turn on one
// thread pool, so a keyframe drawn in one batch holds up every sprite frame
// queued behind it for its whole raster time. Drawn in pieces of about this
// many triangles, each drained before the next, the wait is one piece.
constexpr long long kTrianglesPerPiece = 16384;

struct AsyncKeyframes::Slot {
  enum class State { kFree, kRendering, kLanded, kHeld };
  State state = State::kFree;
  std::unique_ptr<Keyframe> key;  // made and freed in the worker's context
  GLsync landed = nullptr;        // worker -> caller: the textures are complete
  GLsync freed = nullptr;         // caller -> worker: the caller's last sampling is done
};

AsyncKeyframes::AsyncKeyframes(const GlContext& share, const Terrain& terrain, GridMaker make_grid,
                               int width, int height, bool lighting, bool contrast,
                               TerrainShading shading, KeyframeFraming framing)
    : make_grid_(std::move(make_grid)),
      width_(width),
      height_(height),
      lighting_(lighting),
      contrast_(contrast),
      shading_(shading),
      framing_(framing) {
  std::unique_ptr<GlContext> context = share.create_shared();
  worker_ = std::thread(&AsyncKeyframes::run, this, std::move(context), std::cref(terrain));
  std::unique_lock lock(mutex_);
  wake_.wait(lock, [&] { return started_; });
  if (start_error_) {
    lock.unlock();
    worker_.join();
    std::rethrow_exception(start_error_);
  }
}

AsyncKeyframes::~AsyncKeyframes() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void AsyncKeyframes::run(std::unique_ptr<GlContext> context, const Terrain& terrain) {
  std::unique_ptr<Scene> scene;
  try {
    context->make_current();
    scene = std::make_unique<Scene>(terrain);
    scene->set_shading(shading_);
    scene->prepare(0);
  } catch (...) {
    scene.reset();
    context->release_current();
    std::lock_guard lock(mutex_);
    start_error_ = std::current_exception();
    started_ = true;
    wake_.notify_all();
    return;
  }
  std::unique_lock lock(mutex_);
  started_ = true;
  wake_.notify_all();
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || pending_; });
    if (stop_) break;
    const Camera camera = *pending_;
    pending_.reset();
    rendering_ = true;
    Slot* slot = nullptr;
    for (auto& s : slots_)
      if (s->state == Slot::State::kFree) slot = s.get();
    if (!slot) {
      slots_.push_back(std::make_unique<Slot>());
      slot = slots_.back().get();
      slot->key = std::make_unique<Keyframe>(width_, height_, contrast_, framing_);
    }
    slot->state = Slot::State::kRendering;
    const GLsync freed = std::exchange(slot->freed, nullptr);
    lock.unlock();
    if (freed) {
      glWaitSync(freed, 0, GL_TIMEOUT_IGNORED);
      glDeleteSync(freed);
    }
    const auto t0 = std::chrono::steady_clock::now();
    render(*slot, camera, scene->terrain_gpu());
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    lock.lock();
    rendering_ = false;
    ++finished_;
    last_render_ms_ = ms;
    if (discard_) {
      discard_ = false;
      glDeleteSync(std::exchange(slot->landed, nullptr));
      slot->state = Slot::State::kFree;
    } else {
      slot->state = Slot::State::kLanded;
    }
    wake_.notify_all();
  }
  // The GL objects of this context go with it: fences, keyframes, the scene.
  for (auto& s : slots_) {
    if (s->landed) glDeleteSync(s->landed);
    if (s->freed) glDeleteSync(s->freed);
  }
  slots_.clear();
  lock.unlock();
  scene.reset();
  glFinish();
  context->release_current();
}

void AsyncKeyframes::render(Slot& slot, const Camera& camera, TerrainGpu& terrain) {
  // capture() reads the depth back, so the worker's pipeline is drained; the
  // fence still orders the caller's sampling after it, and the flush makes
  // sure the fence reaches the GL server before the caller waits on it.
  const long long triangles = terrain.mesh(0).triangles;
  const int pieces = int(std::clamp<long long>(triangles / kTrianglesPerPiece, 1, 1024));
  slot.key->capture(terrain, make_grid_(camera), camera, lighting_, pieces);
  slot.landed = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  glFlush();
}

bool AsyncKeyframes::busy() const {
  std::lock_guard lock(mutex_);
  if (pending_ || rendering_) return true;
  for (const auto& s : slots_)
    if (s->state == Slot::State::kLanded) return true;
  return false;
}

void AsyncKeyframes::request(const Camera& camera) {
  {
    std::lock_guard lock(mutex_);
    assert(!pending_ && !rendering_);
    pending_ = camera;
  }
  wake_.notify_all();
}

const Keyframe* AsyncKeyframes::take_locked(std::unique_lock<std::mutex>&) {
  for (auto& s : slots_)
    if (s->state == Slot::State::kLanded) {
      s->state = Slot::State::kHeld;
      // Later commands of the caller's context wait for the worker's render.
      const GLsync landed = std::exchange(s->landed, nullptr);
      glWaitSync(landed, 0, GL_TIMEOUT_IGNORED);
      glDeleteSync(landed);
      return s->key.get();
    }
  return nullptr;
}

const Keyframe* AsyncKeyframes::take() {
  std::unique_lock lock(mutex_);
  return take_locked(lock);
}

const Keyframe* AsyncKeyframes::wait() {
  std::unique_lock lock(mutex_);
  wake_.wait(lock, [&] { return !pending_ && !rendering_; });
  return take_locked(lock);
}

void AsyncKeyframes::wait_landed() {
  std::unique_lock lock(mutex_);
  wake_.wait(lock, [&] { return !pending_ && !rendering_; });
}

void AsyncKeyframes::give_back(const Keyframe* key) {
  std::lock_guard lock(mutex_);
  for (auto& s : slots_)
    if (s->key.get() == key) {
      assert(s->state == Slot::State::kHeld);
      s->freed = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
      glFlush();
      s->state = Slot::State::kFree;
      return;
    }
  assert(false && "give_back: not a keyframe of this worker");
}

void AsyncKeyframes::cancel() {
  std::lock_guard lock(mutex_);
  pending_.reset();
  discard_ = rendering_;
  for (auto& s : slots_)
    if (s->state == Slot::State::kLanded) {
      glDeleteSync(std::exchange(s->landed, nullptr));
      s->state = Slot::State::kFree;
    }
}

long long AsyncKeyframes::finished() const {
  std::lock_guard lock(mutex_);
  return finished_;
}

double AsyncKeyframes::last_render_ms() const {
  std::lock_guard lock(mutex_);
  return last_render_ms_;
}

}  // namespace terrasprite
