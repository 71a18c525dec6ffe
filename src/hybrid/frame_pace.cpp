// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/frame_pace.h"

#include <algorithm>
#include <cmath>

namespace terrasprite {

FramePace::FramePace(const FramePaceOptions& options) : o_(options) {
  o_.window = std::max(1, o_.window);
  o_.prior_frames = std::max(0.0, o_.prior_frames);
  o_.max_slope = std::max(0.0, o_.max_slope);
}

void FramePace::observe(double x, double log_residual) {
  if (!std::isfinite(x) || !std::isfinite(log_residual)) return;
  frames_.emplace_back(x, log_residual);
  while (int(frames_.size()) > o_.window) frames_.pop_front();
}

double FramePace::slope() const {
  if (int(frames_.size()) < std::max(2, o_.min_frames)) return 0;
  double mx = 0, mr = 0;
  for (const auto& [x, r] : frames_) mx += x, mr += r;
  mx /= double(frames_.size());
  mr /= double(frames_.size());
  // Least squares of the residual on x about their means (the residual's
  // mean is the refit's and the controller's business), ridge towards 0.
  double sxx = o_.prior_frames * 0.01, sxr = 0;
  for (const auto& [x, r] : frames_) {
    sxx += (x - mx) * (x - mx);
    sxr += (x - mx) * (r - mr);
  }
  return sxx > 0 ? std::clamp(sxr / sxx, 0.0, o_.max_slope) : 0.0;
}

double FramePace::factor(double z) const {
  return std::isfinite(z) ? std::exp(slope() * z) : 1.0;
}

}  // namespace terrasprite
