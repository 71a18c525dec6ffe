// SPDX-License-Identifier: MIT
// Every K-th frame real, the rest warped from the last real one.
#include "terrasprite/warp_renderer.h"

#include <fmt/format.h>

#include "terrasprite/error.h"

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

Frame WarpScheduler::draw(const Camera& camera) {
  const bool real = count_++ % o_.real_every == 0;
  if (real) {
    Frame f =
        real_.render(with_margin(camera, w_, h_, o_.margin_x, o_.margin_y), ReadBack::kColorDepth);
    if (f.width() != w_ + 2 * o_.margin_x || f.height() != h_ + 2 * o_.margin_y)
      throw InputError(fmt::format("warp: real renderer gave {}x{}, expected {}x{}", f.width(),
                                   f.height(), w_ + 2 * o_.margin_x, h_ + 2 * o_.margin_y));
    previous_ = std::move(last_);
    last_ = std::make_unique<Frame>(std::move(f));
    // The same camera: the warp returns the central pixels exactly.
    WarpOptions crop = o_.warp;
    crop.method = WarpMethod::kPoly2;
    crop.keep_sources = false;
    warper_.warp(*last_, camera, w_, h_, crop);
    WarpedFrame out = warper_.take();
    out.frame.cls = last_->cls;
    out.frame.ms += last_->ms;
    out.frame.gpu_ms = last_->gpu_ms;
    out.frame.triangles = last_->triangles;
    last_holes_ = 0;
    return std::move(out.frame);
  }
  const Frame* second = o_.second_reference ? previous_.get() : nullptr;
  warper_.warp(*last_, camera, w_, h_, o_.warp, second);
  WarpedFrame out = warper_.take();
  last_holes_ = out.hole_fraction;
  return std::move(out.frame);
}

}  // namespace terrasprite
