// SPDX-License-Identifier: MIT
// Table lookup of Jehaes, Lamotte & Tack (GRAPP 2008), section 3.3, with
// interpolation between the measured views and sizes instead of the nearest.
#include "terrasprite/hybrid/expected_quality.h"

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

/// Degrees into [0, 360).
double wrap_degrees(double deg) {
  double w = std::fmod(deg, 360.0);
  if (w < 0) w += 360.0;
  return w >= 360.0 ? 0.0 : w;  // -1e-20 + 360 rounds to 360
}

/// Weighted sums of SSIM, SSIM squared and PSNR over samples.
struct Moments {
  double ssim = 0, ssim_sq = 0, psnr = 0;
};

Moments lerp(const Moments& a, const Moments& b, double t) {
  return {a.ssim + t * (b.ssim - a.ssim), a.ssim_sq + t * (b.ssim_sq - a.ssim_sq),
          a.psnr + t * (b.psnr - a.psnr)};
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
    const double heading = wrap_degrees(s.heading_deg);
    auto h = std::find_if(it->headings.begin(), it->headings.end(),
                          [&](const HeadingSlice& hs) { return hs.heading_deg == heading; });
    if (h == it->headings.end()) {
      it->headings.push_back({heading, {}});
      h = it->headings.end() - 1;
    }
    const glm::dvec3 d = direction(s.phi_deg, s.theta_deg);
    h->samples.push_back({d.x, d.y, d.z, {s.ssim, capped_psnr(s.psnr)}});
    theta_max_ = std::max(theta_max_, s.theta_deg);
  }
  std::sort(slices_.begin(), slices_.end(),
            [](const SizeSlice& a, const SizeSlice& b) { return a.size_px < b.size_px; });
  for (SizeSlice& sl : slices_) {
    std::sort(
        sl.headings.begin(), sl.headings.end(),
        [](const HeadingSlice& a, const HeadingSlice& b) { return a.heading_deg < b.heading_deg; });
    for (const HeadingSlice& h : sl.headings)
      sl.shared_views = sl.shared_views && same_views(h.samples, sl.headings.front().samples);
  }
}

std::array<std::pair<int, double>, 4> QualityInterpolator::nearest(
    const std::vector<Direction>& samples, double x, double y, double z) {
  // The four nearest samples by angle (largest cosine), weighted by inverse angle.
  std::array<std::pair<double, int>, 4> best;
  best.fill({-2.0, -1});
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const Direction& d = samples[k];
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
                                                          double size_px,
                                                          double heading_deg) const {
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
  const double heading = wrap_degrees(heading_deg);
  for (int s = 0; s < w.slices; ++s) {
    const auto& hs = slices_[std::size_t(w.slice[std::size_t(s)])].headings;
    // The measured headings around the asked one, across 360 where it lies
    // past the last (or before the first) of them.
    std::size_t hi = 0;
    while (hi < hs.size() && hs[hi].heading_deg <= heading) ++hi;
    const std::size_t h0 = (hi + hs.size() - 1) % hs.size(), h1 = hi % hs.size();
    double gap = hs[h1].heading_deg - hs[h0].heading_deg, past = heading - hs[h0].heading_deg;
    if (gap <= 0) gap += 360;
    if (past < 0) past += 360;
    w.heading[std::size_t(s)] = {int(h0), int(h1)};
    w.u[std::size_t(s)] = h0 == h1 ? 0.0 : past / gap;
    auto& n = w.nearest[std::size_t(s)];
    n[0] = nearest(hs[h0].samples, d.x, d.y, d.z);
    const bool same = h0 == h1 || slices_[std::size_t(w.slice[std::size_t(s)])].shared_views;
    n[1] = same ? n[0] : nearest(hs[h1].samples, d.x, d.y, d.z);
  }
  return w;
}

ExpectedQuality QualityInterpolator::at(const Weights& w) const {
  if (w.slices == 0 || slices_.empty()) return {};
  Moments q[2];
  for (std::size_t s = 0; s < std::size_t(w.slices); ++s) {
    const SizeSlice& slice = slices_[std::size_t(w.slice[s])];
    Moments by_heading[2];
    for (std::size_t h = 0; h < 2; ++h) {
      const auto& samples = slice.headings[std::size_t(w.heading[s][h])].samples;
      for (const auto& [k, weight] : w.nearest[s][h]) {
        if (k < 0) continue;
        const ExpectedQuality& v = samples[std::size_t(k)].q;
        by_heading[h].ssim += weight * v.ssim;
        by_heading[h].ssim_sq += weight * v.ssim * v.ssim;
        by_heading[h].psnr += weight * v.psnr;
      }
    }
    q[s] = lerp(by_heading[0], by_heading[1], w.u[s]);
  }
  const Moments m = w.slices == 1 ? q[0] : lerp(q[0], q[1], w.t);
  return {m.ssim, m.psnr, std::sqrt(std::max(0.0, m.ssim_sq - m.ssim * m.ssim))};
}

ExpectedQuality QualityInterpolator::at(double phi_deg, double theta_deg, double size_px,
                                        double heading_deg) const {
  return at(weights(phi_deg, theta_deg, size_px, heading_deg));
}

bool QualityInterpolator::same_views(const std::vector<Direction>& a,
                                     const std::vector<Direction>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (std::abs(a[k].x - b[k].x) > 1e-9 || std::abs(a[k].y - b[k].y) > 1e-9 ||
        std::abs(a[k].z - b[k].z) > 1e-9)
      return false;
  return true;
}

bool QualityInterpolator::same_layout(const QualityInterpolator& other) const {
  if (slices_.size() != other.slices_.size()) return false;
  for (std::size_t s = 0; s < slices_.size(); ++s) {
    const SizeSlice &a = slices_[s], &b = other.slices_[s];
    if (a.size_px != b.size_px || a.headings.size() != b.headings.size()) return false;
    for (std::size_t h = 0; h < a.headings.size(); ++h) {
      const HeadingSlice &ha = a.headings[h], &hb = b.headings[h];
      if (ha.heading_deg != hb.heading_deg || !same_views(ha.samples, hb.samples)) return false;
    }
  }
  return true;
}

}  // namespace terrasprite
