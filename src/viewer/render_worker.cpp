// SPDX-License-Identifier: MIT
#include "viewer/render_worker.h"

#include <epoxy/gl.h>

#include <chrono>
#include <utility>

#include "gl/gl_objects.h"
#include "terrasprite/gl/gl_renderer.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite::viewer {

/// Three colour (RGBA8) + depth (32F) targets of one size, made on the worker's context.
struct RenderWorker::Targets {
  struct Slot {
    gl::Texture color{GL_TEXTURE_2D}, depth{GL_TEXTURE_2D};
    gl::Framebuffer fbo;
  };
  std::array<Slot, 3> slots;
  int width, height;

  Targets(int w, int h) : width(w), height(h) {
    for (Slot& s : slots) {
      glTextureStorage2D(s.color.id(), 1, GL_RGBA8, w, h);
      glTextureParameteri(s.color.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(s.color.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureStorage2D(s.depth.id(), 1, GL_DEPTH_COMPONENT32F, w, h);
      glNamedFramebufferTexture(s.fbo.id(), GL_COLOR_ATTACHMENT0, s.color.id(), 0);
      glNamedFramebufferTexture(s.fbo.id(), GL_DEPTH_ATTACHMENT, s.depth.id(), 0);
    }
  }
  GlTarget target(int i) const { return {slots[std::size_t(i)].fbo.id(), width, height}; }
};

RenderWorker::RenderWorker(ViewRendererFactory factory, ContextFactory context)
    : factory_(std::move(factory)), context_(std::move(context)) {
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
  std::optional<RenderedFrame> f;
  {
    std::lock_guard lock(m_);
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    if (done_) shown_slot_ = done_->slot;
    f = std::exchange(done_, std::nullopt);
  }
  if (f) cv_.notify_all();  // the worker waits for its last frame to be taken
  return f;
}

void RenderWorker::wait(double timeout_s) {
  std::unique_lock lock(m_);
  cv_.wait_for(lock, std::chrono::duration<double>(timeout_s),
               [&] { return done_.has_value() || error_ || stop_; });
}

void RenderWorker::request_compare() {
  {
    std::lock_guard lock(m_);
    compare_ = true;
  }
  cv_.notify_all();
}

Comparison RenderWorker::compare(ViewRenderer& r, RenderedFrame& shown, const Camera& camera,
                                 std::unique_ptr<ViewRenderer>& reference, GlContext* context) {
  if (!reference) {
    LiveSettings full;
    full.mode = RenderMode::kFull;
    reference = factory_(full, context);
  }
  Frame test = shown.frame;
  if (test.color.rgba.empty()) r.renderer().read_back(test, ReadBack::kColor);
  const Frame ref = reference->renderer().render(camera, ReadBack::kColor);
  Comparison c;
  const ImageView a = ref.color.view(), b = test.color.view();
  c.psnr = quality::psnr(a, b).rgb;
  c.ssim = quality::ssim(a, b).ssim;
  c.flip = quality::flip(a, b).mean;
  c.difference = quality::difference_image(a, b);
  c.mode = shown.settings.mode;
  return c;
}

bool RenderWorker::building() const {
  std::lock_guard lock(m_);
  return building_;
}

RenderedFrame RenderWorker::draw(ViewRenderer& r, const Camera& camera, Targets* targets) {
  RenderedFrame out;
  auto* gl_renderer = dynamic_cast<GlRenderer*>(&r.renderer());
  if (gl_renderer && targets) {
    // A slot neither on screen nor waiting to be shown (three make one free).
    int slot = 0;
    {
      std::lock_guard lock(m_);
      const int pending = done_ ? done_->slot : -1;
      while (slot == shown_slot_ || slot == pending) ++slot;
    }
    gl_renderer->set_output(targets->target(slot));
    out.frame = gl_renderer->draw(camera);
    glFinish();  // complete before the window's context samples it
    out.texture = targets->slots[std::size_t(slot)].color.id();
    out.slot = slot;
  } else {
    out.frame = r.renderer().render(camera, ReadBack::kColor);
  }
  out.error_px = r.error_px();
  out.landed = r.landed_keyframe();
  out.keyframes = r.keyframe_stats();
  out.device = r.device();
  return out;
}

void RenderWorker::loop() {
  std::unique_ptr<GlContext> context;
  std::unique_ptr<Targets> targets;
  std::unique_ptr<ViewRenderer> renderer, reference;
  LiveSettings built;
  try {
    if (context_) context = context_();
    for (;;) {
      Camera camera;
      std::uint64_t generation = 0;
      LiveSettings settings;
      bool compare = false;
      {
        std::unique_lock lock(m_);
        // A finished frame not yet taken is not drawn over: a frame nobody
        // sees would only take the CPU from the window and from a keyframe
        // worker (LOD-sprite's second thread), and take() wakes us at once.
        cv_.wait(lock, [&] { return stop_ || (has_request_ && !done_); });
        if (stop_) break;
        compare = std::exchange(compare_, false);
        camera = camera_;
        generation = generation_;
        settings = settings_;
        building_ = !renderer || !(settings == built);
      }
      if (!renderer || !(settings == built)) {
        renderer.reset();  // one renderer at a time
        renderer = factory_(settings, context.get());
        built = settings;
        // Every renderer of a run has the window's render size: one set of targets.
        auto* g = dynamic_cast<GlRenderer*>(&renderer->renderer());
        if (context && g && !targets) targets = std::make_unique<Targets>(g->width(), g->height());
        std::lock_guard lock(m_);
        building_ = false;
      }
      RenderedFrame r = draw(*renderer, camera, targets.get());
      r.generation = generation;
      r.settings = settings;
      if (compare) r.comparison = this->compare(*renderer, r, camera, reference, context.get());
      {
        std::lock_guard lock(m_);
        // A frame not yet taken is replaced by the newer one, but not its comparison.
        if (done_ && done_->comparison && !r.comparison)
          r.comparison = std::move(done_->comparison);
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
  reference.reset();
  targets.reset();
  if (context) context->release_current();
}

}  // namespace terrasprite::viewer
