// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/quality_calibration.h"

#include <gtest/gtest.h>

#include <vector>

namespace terrasprite {
namespace {

TEST(QualityCalibration, FitsTheErrorScaleAndRewritesTheSamples) {
  // In context the error is three times the table's (octahedral forest, 0.78 -> 0.34).
  const ErrorScaleOptions exact{.prior_weight = 0};
  std::vector<QualityObservation> obs;
  for (double p : {0.95, 0.9, 0.8, 0.7}) obs.push_back({p, 1 - 3 * (1 - p), 100});
  EXPECT_NEAR(fit_error_scale(obs, exact), 3.0, 1e-12);
  // Weighted: a heavy group decides.
  obs = {{0.9, 0.95, 1000}, {0.9, 0.5, 1}};
  EXPECT_NEAR(fit_error_scale(obs, exact), (1000 * 0.1 * 0.05 + 0.1 * 0.5) / (1001 * 0.01), 1e-12);
  // Clamped; nothing usable (no weight, identical predictions) reads 1.
  EXPECT_EQ(fit_error_scale(std::vector<QualityObservation>{{0.99, 0.0, 1}}, exact), 8.0);
  EXPECT_EQ(fit_error_scale(std::vector<QualityObservation>{{0.99, 1.0, 1}}, exact), 0.25);
  EXPECT_EQ(fit_error_scale(std::vector<QualityObservation>{{1.0, 0.5, 1}, {0.8, 0.5, 0}}), 1.0);
  EXPECT_EQ(fit_error_scale({}), 1.0);
  // The prior: 5 px scoring 0 for a predicted 0.9 move k little; 20000 px decide.
  EXPECT_LT(fit_error_scale(std::vector<QualityObservation>{{0.9, 0.0, 5}}), 1.5);
  EXPECT_NEAR(fit_error_scale(std::vector<QualityObservation>{{0.9, 0.7, 20000}}), 3.0, 0.03);

  EXPECT_DOUBLE_EQ(scaled_ssim(0.9, 2), 0.8);
  EXPECT_DOUBLE_EQ(scaled_ssim(0.5, 4), 0.0);
  EXPECT_DOUBLE_EQ(scaled_ssim(1.0, 8), 1.0);
  RepresentationQuality rq;
  rq.samples = {{0, 90, 16, 30, 0.9}, {45, 90, 16, 25, 0.6}};
  apply_error_scale(rq, 0.5);
  EXPECT_DOUBLE_EQ(rq.samples[0].ssim, 0.95);
  EXPECT_DOUBLE_EQ(rq.samples[1].ssim, 0.8);
  EXPECT_EQ(rq.samples[1].psnr, 25);
}

}  // namespace
}  // namespace terrasprite
