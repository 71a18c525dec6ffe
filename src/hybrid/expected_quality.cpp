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

ExpectedQuality QualityInterpolator::at_size(const SizeSlice& slice, double x, double y,
                                             double z) const {
  // The four nearest samples by angle (largest cosine), weighted by inverse angle.
  std::array<std::pair<double, const Direction*>, 4> nearest;
  nearest.fill({-2.0, nullptr});
  for (const Direction& d : slice.samples) {
    const double cosine = d.x * x + d.y * y + d.z * z;
    if (cosine > nearest.back().first) {
      nearest.back() = {cosine, &d};
      std::sort(nearest.begin(), nearest.end(),
                [](const auto& a, const auto& b) { return a.first > b.first; });
    }
  }
  if (nearest.front().first > 1.0 - 1e-12) return nearest.front().second->q;
  ExpectedQuality sum{0, 0};
  double wsum = 0;
  for (const auto& [cosine, d] : nearest) {
    if (!d) continue;
    const double w = 1.0 / std::acos(std::clamp(cosine, -1.0, 1.0));
    sum.ssim += w * d->q.ssim;
    sum.psnr += w * d->q.psnr;
    wsum += w;
  }
  return {sum.ssim / wsum, sum.psnr / wsum};
}

ExpectedQuality QualityInterpolator::at(double phi_deg, double theta_deg, double size_px) const {
  if (slices_.empty()) return {};
  const glm::dvec3 d = direction(phi_deg, std::clamp(theta_deg, 0.0, theta_max_));
  if (size_px <= slices_.front().size_px) return at_size(slices_.front(), d.x, d.y, d.z);
  if (size_px >= slices_.back().size_px) return at_size(slices_.back(), d.x, d.y, d.z);
  std::size_t i = 1;
  while (slices_[i].size_px < size_px) ++i;
  const SizeSlice& a = slices_[i - 1];
  const SizeSlice& b = slices_[i];
  const double t = std::log2(size_px / a.size_px) / std::log2(b.size_px / a.size_px);
  const ExpectedQuality qa = at_size(a, d.x, d.y, d.z), qb = at_size(b, d.x, d.y, d.z);
  return {qa.ssim + t * (qb.ssim - qa.ssim), qa.psnr + t * (qb.psnr - qa.psnr)};
}

}  // namespace terrasprite
