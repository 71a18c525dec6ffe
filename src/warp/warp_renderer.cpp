// SPDX-License-Identifier: MIT
// Every K-th frame real, the rest warped from the last real one.
#include "terrasprite/warp/warp_renderer.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstring>

#include "terrasprite/common/error.h"

namespace terrasprite {

WarpScheduler::WarpScheduler(Renderer& real, int width, int height, WarpScheduleOptions options)
    : real_(real), w_(width), h_(height), o_(options) {
  if (o_.real_every < 1)
    throw InputError(fmt::format("real_every {}: must be at least 1", o_.real_every));
  if (o_.margin_x < 0 || o_.margin_y < 0)
    throw InputError(
        fmt::format("warp margin {}x{}: must not be negative", o_.margin_x, o_.margin_y));
  if (width < 1 || height < 1)
    throw InputError(fmt::format("warp output size {}x{}: out of range", width, height));
}

WarpScheduler::~WarpScheduler() = default;

std::string WarpScheduler::name() const {
  return fmt::format("{}+warp-{}-every-{}", real_.name(), to_string(o_.warp.method), o_.real_every);
}

namespace {

// The central w x h pixels of `src` (colour and depth) into `out`, whose
// buffers are kept when their size fits: what warping the margin frame back
// to its own camera returns, without the warp's fit and bilinear reads.
void crop(const Frame& src, int x0, int y0, int w, int h, Frame& out) {
  out.prepare_for_overwrite(w, h);
  const int sw = src.color.width;
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 32), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      std::memcpy(out.color.px(0, y), src.color.rgba.data() + (std::size_t(y + y0) * sw + x0) * 4,
                  std::size_t(w) * 4);
      std::memcpy(out.depth.data() + std::size_t(y) * w,
                  src.depth.data() + std::size_t(y + y0) * sw + x0, std::size_t(w) * sizeof(float));
    }
  });
}

}  // namespace

Frame WarpScheduler::draw(const Camera& camera) {
  Frame out;
  draw_into(camera, out);
  return out;
}

void WarpScheduler::draw_into(const Camera& camera, Frame& target) {
  const bool real = count_++ % o_.real_every == 0;
  if (real) {
    // The frame two real frames back is no longer read: its buffers take the
    // new one.
    std::unique_ptr<Frame> f = previous_ ? std::move(previous_) : std::make_unique<Frame>();
    real_.draw_into(with_margin(camera, w_, h_, o_.margin_x, o_.margin_y), *f);
    real_.read_back(*f, ReadBack::kColorDepth);
    if (f->width() != w_ + 2 * o_.margin_x || f->height() != h_ + 2 * o_.margin_y ||
        f->depth.size() != std::size_t(f->width()) * f->height())
      throw InputError(fmt::format("warp: real renderer gave {}x{}, expected {}x{} with depth",
                                   f->width(), f->height(), w_ + 2 * o_.margin_x,
                                   h_ + 2 * o_.margin_y));
    previous_ = std::move(last_);
    last_ = std::move(f);
    // The same camera: the central pixels.
    const auto start = std::chrono::steady_clock::now();
    crop(*last_, o_.margin_x, o_.margin_y, w_, h_, target);
    target.ms =
        last_->ms +
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    target.cls = last_->cls;
    target.camera = camera;
    target.gpu_ms = last_->gpu_ms;
    target.triangles = last_->triangles;
    return;
  }
  const Frame* second = o_.second_reference ? previous_.get() : nullptr;
  warper_.warp(*last_, camera, w_, h_, o_.warp, second);
  warper_.exchange(target);
}

}  // namespace terrasprite
