// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/quality_calibration.h"

#include <algorithm>

namespace terrasprite {

double fit_error_scale(std::span<const QualityObservation> obs, const ErrorScaleOptions& o) {
  double num = 0, den = 0;
  for (const QualityObservation& q : obs) {
    const double ep = 1 - q.predicted, em = 1 - q.measured;
    if (!(q.weight > 0) || !(ep >= o.min_predicted_error) || !std::isfinite(em)) continue;
    num += q.weight * ep * em;
    den += q.weight * ep * ep;
  }
  const double prior = o.prior_weight * 0.01;
  num += prior;
  den += prior;
  if (!(den > 0)) return 1.0;
  return std::clamp(num / den, o.min_scale, o.max_scale);
}

double scaled_ssim(double ssim, double k) {
  return std::clamp(1 - k * (1 - ssim), 0.0, 1.0);
}

void apply_error_scale(RepresentationQuality& rep, double k) {
  for (QualitySample& s : rep.samples) s.ssim = scaled_ssim(s.ssim, k);
}

}  // namespace terrasprite
