// SPDX-License-Identifier: MIT
// warp_frame(): checks the references, sizes the output, runs one method,
// times it.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "terrasprite/common/error.h"
#include "warp/warp_internal.h"

namespace terrasprite {

WarpMethod parse_warp_method(const std::string& text) {
  if (text == "poly2") return WarpMethod::kPoly2;
  if (text == "depth") return WarpMethod::kDepth;
  throw InputError(fmt::format("warp method '{}': expected poly2 or depth", text));
}

const char* to_string(WarpMethod m) {
  return m == WarpMethod::kPoly2 ? "poly2" : "depth";
}

namespace {

// The number of 1s in a 0/1 mask, summed in 32-bit chunks (the inner loop
// vectorises; a size_t accumulator per byte does not).
std::size_t count_ones(const std::vector<std::uint8_t>& mask) {
  std::size_t total = 0;
  constexpr std::size_t kChunk = std::size_t(1) << 24;
  for (std::size_t b = 0; b < mask.size(); b += kChunk) {
    const std::size_t e = std::min(mask.size(), b + kChunk);
    std::uint32_t sum = 0;
    for (std::size_t i = b; i < e; ++i) sum += mask[i];
    total += sum;
  }
  return total;
}

void check_reference(const Frame& f, const char* what) {
  const std::size_t n = std::size_t(std::max(f.width(), 0)) * std::max(f.height(), 0);
  if (f.width() < 1 || f.height() < 1 || f.width() > 16384 || f.height() > 16384)
    throw InputError(
        fmt::format("warp: {} frame size {}x{} out of range", what, f.width(), f.height()));
  if (f.depth.size() != n)
    throw InputError(fmt::format("warp: {} frame has no depth ({} values for {}x{} pixels)", what,
                                 f.depth.size(), f.width(), f.height()));
}

}  // namespace

Warper::Warper() : scratch_(std::make_unique<Scratch>()) {}
Warper::~Warper() = default;
Warper::Warper(Warper&&) noexcept = default;
Warper& Warper::operator=(Warper&&) noexcept = default;

const WarpedFrame& Warper::warp(const Frame& real, const Camera& target, int width, int height,
                                const WarpOptions& options, const Frame* second) {
  check_reference(real, "real");
  if (second) check_reference(*second, "second reference");
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw InputError(fmt::format("warp: output size {}x{} out of range", width, height));
  const auto start = std::chrono::steady_clock::now();
  WarpedFrame& r = result_;
  const std::size_t n = std::size_t(width) * height;
  r.frame.prepare_for_overwrite(width, height);  // the methods write every pixel
  r.holes.resize(n);
  r.source_x.resize(options.keep_sources ? n : 0);
  r.source_y.resize(options.keep_sources ? n : 0);
  r.frame.cls = FrameClass::kWarp;
  r.frame.camera = target;
  const warp::Reference ref(real);
  const warp::Pinhole out(target, width, height);
  if (options.method == WarpMethod::kPoly2) {
    warp::warp_poly2(ref, out, options, r);
  } else {
    std::optional<warp::Reference> ref2;
    if (second) ref2.emplace(*second);
    warp::warp_depth(ref, ref2 ? &*ref2 : nullptr, out, options, r, *scratch_);
  }
  r.frame.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  r.hole_fraction = double(count_ones(r.holes)) / double(n);
  return r;
}

WarpedFrame Warper::take() {
  return std::move(result_);
}

void Warper::exchange(Frame& frame) {
  std::swap(result_.frame, frame);
}

WarpedFrame warp_frame(const Frame& real, const Camera& target, int width, int height,
                       const WarpOptions& options, const Frame* second) {
  Warper w;
  w.warp(real, target, width, height, options, second);
  return w.take();
}

Camera with_margin(const Camera& camera, int width, int height, int margin_x, int margin_y) {
  Camera c = camera;
  const double t = std::tan(camera.fov_y_deg * kRadiansPerDegree * 0.5);
  const int wm = width + 2 * margin_x, hm = height + 2 * margin_y;
  // Same focal length in pixels: tan grows with the image's half-height;
  // the horizontal focal length must match too, which fixes the aspect.
  const double fx = width / (2.0 * t * camera.aspect);
  const double tm = t * double(hm) / double(height);
  c.fov_y_deg = 2.0 * std::atan(tm) / kRadiansPerDegree;
  c.aspect = double(wm) / (2.0 * tm * fx);
  return c;
}

}  // namespace terrasprite
