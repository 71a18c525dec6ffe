// SPDX-License-Identifier: MIT
// Table lookup of Jehaes, Lamotte & Tack (GRAPP 2008), section 3.3, with
// interpolation between the measured views and sizes instead of the nearest.
#include "terrasprite/expected_quality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/glm.hpp>

namespace terrasprite {
namespace {

glm::dvec3 direction(double phi_deg, double theta_deg) {
  const double p = glm::radians(phi_deg), t = glm::radians(theta_deg);
  return {std::sin(t) * std::sin(p), std::sin(t) * std::cos(p), std::cos(t)};
}

double capped_psnr(double psnr) {
  return std::isfinite(psnr) ? std::min(psnr, 100.0) : 100.0;
}

}  // namespace

QualityInterpolator::QualityInterpolator(const RepresentationQuality& rep) {
  theta_max_ = 0;
  for (const QualitySample& s : rep.samples) {
    // A sample without a score (NaN: nothing was measured there) is no
    // evidence: the nearest scored views stand in for it.
    if (!std::isfinite(s.ssim)) continue;
    auto it = std::find_if(slices_.begin(), slices_.end(),
                           [&](const SizeSlice& sl) { return sl.size_px == s.size_px; });
    if (it == slices_.end()) {
      slices_.push_back({double(s.size_px), {}});
      it = slices_.end() - 1;
    }
    const glm::dvec3 d = direction(s.phi_deg, s.theta_deg);
    it->samples.push_back({d.x, d.y, d.z, {s.ssim, capped_psnr(s.psnr)}});
    theta_max_ = std::max(theta_max_, s.theta_deg);
  }
  std::sort(slices_.begin(), slices_.end(),
            [](const SizeSlice& a, const SizeSlice& b) { return a.size_px < b.size_px; });
}

std::array<std::pair<int, double>, 4> QualityInterpolator::nearest(const SizeSlice& slice, double x,
                                                                   double y, double z) const {
  // The four nearest samples by angle (largest cosine), weighted by inverse angle.
  std::array<std::pair<double, int>, 4> best;
  best.fill({-2.0, -1});
  for (std::size_t k = 0; k < slice.samples.size(); ++k) {
    const Direction& d = slice.samples[k];
    const double cosine = d.x * x + d.y * y + d.z * z;
    if (cosine <= best[3].first) continue;
    int j = 3;
    while (j > 0 && best[std::size_t(j - 1)].first < cosine) {
      best[std::size_t(j)] = best[std::size_t(j - 1)];
      --j;
    }
    best[std::size_t(j)] = {cosine, int(k)};
  }
  std::array<std::pair<int, double>, 4> out;
  out.fill({-1, 0.0});
  if (best[0].first > 1.0 - 1e-12) {
    out[0] = {best[0].second, 1.0};
    return out;
  }
  double wsum = 0;
  for (std::size_t j = 0; j < 4; ++j) {
    if (best[j].second < 0) continue;
    const double w = 1.0 / std::acos(std::clamp(best[j].first, -1.0, 1.0));
    out[j] = {best[j].second, w};
    wsum += w;
  }
  for (auto& [k, w] : out) w /= wsum;
  return out;
}

QualityInterpolator::Weights QualityInterpolator::weights(double phi_deg, double theta_deg,
                                                          double size_px) const {
  Weights w;
  if (slices_.empty()) return w;
  const glm::dvec3 d = direction(phi_deg, std::clamp(theta_deg, 0.0, theta_max_));
  std::size_t a = 0, b = 0;
  if (size_px >= slices_.back().size_px) {
    a = b = slices_.size() - 1;
  } else if (size_px > slices_.front().size_px) {
    b = 1;
    while (slices_[b].size_px < size_px) ++b;
    a = b - 1;
    w.t = std::log2(size_px / slices_[a].size_px) /
          std::log2(slices_[b].size_px / slices_[a].size_px);
  }
  w.slices = a == b ? 1 : 2;
  w.slice = {int(a), int(b)};
  w.nearest[0] = nearest(slices_[a], d.x, d.y, d.z);
  if (a != b) w.nearest[1] = nearest(slices_[b], d.x, d.y, d.z);
  return w;
}

ExpectedQuality QualityInterpolator::at(const Weights& w) const {
  if (w.slices == 0 || slices_.empty()) return {};
  ExpectedQuality q[2];
  for (int s = 0; s < w.slices; ++s) {
    const SizeSlice& slice = slices_[std::size_t(w.slice[std::size_t(s)])];
    q[s] = {0, 0};
    for (const auto& [k, weight] : w.nearest[std::size_t(s)]) {
      if (k < 0) continue;
      q[s].ssim += weight * slice.samples[std::size_t(k)].q.ssim;
      q[s].psnr += weight * slice.samples[std::size_t(k)].q.psnr;
    }
  }
  if (w.slices == 1) return q[0];
  return {q[0].ssim + w.t * (q[1].ssim - q[0].ssim), q[0].psnr + w.t * (q[1].psnr - q[0].psnr)};
}

ExpectedQuality QualityInterpolator::at(double phi_deg, double theta_deg, double size_px) const {
  return at(weights(phi_deg, theta_deg, size_px));
}

bool QualityInterpolator::same_layout(const QualityInterpolator& other) const {
  if (slices_.size() != other.slices_.size()) return false;
  for (std::size_t s = 0; s < slices_.size(); ++s) {
    const SizeSlice &a = slices_[s], &b = other.slices_[s];
    if (a.size_px != b.size_px || a.samples.size() != b.samples.size()) return false;
    for (std::size_t k = 0; k < a.samples.size(); ++k)
      if (std::abs(a.samples[k].x - b.samples[k].x) > 1e-9 ||
          std::abs(a.samples[k].y - b.samples[k].y) > 1e-9 ||
          std::abs(a.samples[k].z - b.samples[k].z) > 1e-9)
        return false;
  }
  return true;
}

}  // namespace terrasprite
