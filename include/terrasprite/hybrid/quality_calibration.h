// SPDX-License-Identifier: MIT
// The quality tables in context. A table is measured on one isolated object
// over the clear colour, the camera 20 degrees wide and level with or above
// it; in a walkthrough the same representation is seen over the terrain,
// from below its centre (a 10 m forest from 1.7 m), near and off-axis. Its
// score there (bench hybrid --quality-diagnosis) differs by representation:
// meshes as predicted or better, octahedral impostors of the forest at 0.3
// for a predicted 0.8. A representation's in-context error is fitted as a
// multiple of its table's: 1 - ssim_scene = k (1 - ssim_table), k from
// instances drawn over the terrain at the walkthrough's own views.
#pragma once
#include <span>

#include "terrasprite/objects/quality_table.h"

namespace terrasprite {

/// One group of instances drawn in context at one representation: the
/// tables' expected SSIM (weighted by the instances' pixels) against the
/// SSIM measured over the pixels they cover, and a weight (those pixels).
struct QualityObservation {
  double predicted = 1, measured = 1, weight = 0;
};

struct ErrorScaleOptions {
  double min_scale = 0.25, max_scale = 8;
  /// Observations whose predicted error is under this say nothing about the
  /// scale (both images nearly identical): skipped.
  double min_predicted_error = 1e-3;
  /// Shrinks k towards 1 for groups of few pixels (a 5 px beetle says little):
  /// as if this many pixels with a predicted error of 0.1 had scored exactly
  /// as predicted.
  double prior_weight = 200;
};

/// k minimising sum w ((1 - measured) - k (1 - predicted))^2 (least squares
/// through the origin) plus the prior's prior_weight 0.1^2 (k - 1)^2, clamped
/// to [min_scale, max_scale]; 1 without usable observations.
double fit_error_scale(std::span<const QualityObservation> obs, const ErrorScaleOptions& o = {});

/// 1 - k (1 - ssim), clamped to [0, 1].
double scaled_ssim(double ssim, double k);

/// Every SSIM sample of `rep` rescaled by k (PSNR is left as measured).
void apply_error_scale(RepresentationQuality& rep, double k);

}  // namespace terrasprite
