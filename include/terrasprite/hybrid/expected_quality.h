// SPDX-License-Identifier: MIT
// Expected image quality of a representation seen from a given direction at
// a given on-screen size, interpolated from its measured quality table
// (QualityTable samples over phi x theta x size_px x heading).
#pragma once
#include <array>
#include <utility>
#include <vector>

#include "terrasprite/objects/quality_table.h"

namespace terrasprite {

struct ExpectedQuality {
  double ssim = 1.0;
  double psnr = 100.0;  ///< dB, capped at 100 (identical images)
  /// Weighted standard deviation of the measured SSIM of the samples this
  /// value is interpolated from (the nearest views, the two headings and
  /// the two sizes around the asked one, with their weights): how much the
  /// quality moves near this view, where the table says only its mean.
  double ssim_spread = 0.0;
};

/// Interpolates one representation's samples: over the view direction by
/// inverse angular distance to the (up to) four nearest samples of each
/// measured size and heading, then linearly in heading between the two
/// measured headings around the asked one (around the circle), then linearly
/// in log2(size) between the two sizes around the asked one (sizes outside
/// the measured range clamp to the nearest). theta beyond the sampled range
/// (a hemisphere table seen from below) clamps to the largest sampled theta.
class QualityInterpolator {
 public:
  /// Copies the samples, less those whose SSIM is not finite (the nearest
  /// scored views stand in for them). A representation without samples (or
  /// a full-detail mesh) reads as perfect quality.
  explicit QualityInterpolator(const RepresentationQuality& rep);
  /// phi in degrees (any range), theta in degrees from straight above, size
  /// in pixels (> 0), the instance's compass heading in degrees (any range;
  /// the sun's side of the model).
  ExpectedQuality at(double phi_deg, double theta_deg, double size_px,
                     double heading_deg = 0) const;

  /// Where a view falls in the table: which samples, with which weights.
  /// Computed once per instance and view, applied to every representation
  /// measured on the same views and sizes (same_layout).
  struct Weights {
    int slices = 0;  ///< 0: no samples (perfect quality)
    std::array<int, 2> slice{0, 0};
    double t = 0;  ///< blend of slice[1] over slice[0]
    /// Per size slice: its two headings around the asked one, and the blend
    /// of the second over the first.
    std::array<std::array<int, 2>, 2> heading{};
    std::array<double, 2> u{0, 0};
    /// [slice][heading]: (sample, weight), weights sum to 1
    std::array<std::array<std::array<std::pair<int, double>, 4>, 2>, 2> nearest{};
  };
  Weights weights(double phi_deg, double theta_deg, double size_px, double heading_deg = 0) const;
  ExpectedQuality at(const Weights& w) const;
  /// Whether `other` has the same sizes, headings and views in the same order.
  bool same_layout(const QualityInterpolator& other) const;

 private:
  struct Direction {
    double x, y, z;  ///< unit view direction of the sample
    ExpectedQuality q;
  };
  struct HeadingSlice {
    double heading_deg = 0;  ///< in [0, 360)
    std::vector<Direction> samples;
  };
  struct SizeSlice {
    double size_px = 0;
    std::vector<HeadingSlice> headings;  ///< rising heading
    /// Every heading measured on the same views in the same order (as
    /// measure_quality_table does): one nearest-view search serves them all.
    bool shared_views = true;
  };
  static std::array<std::pair<int, double>, 4> nearest(const std::vector<Direction>& samples,
                                                       double x, double y, double z);
  /// Whether two sample lists are on the same views in the same order.
  static bool same_views(const std::vector<Direction>& a, const std::vector<Direction>& b);
  std::vector<SizeSlice> slices_;  ///< rising size
  double theta_max_ = 180.0;
};

}  // namespace terrasprite
