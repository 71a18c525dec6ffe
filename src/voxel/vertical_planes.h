// SPDX-License-Identifier: MIT
// Where the vertical planes through the eye lie in the image, so coherent
// columns can be cast along them with the camera pitched or rolled.
#pragma once
#include <cstdint>

#include "terrasprite/camera/camera.h"

namespace terrasprite {

/// Vertical planes through the eye project to image lines through the
/// vertical vanishing point V (the nadir's image). Far from the image (camera
/// near level) the planes are indexed by the slope lambda of their line across
/// an axis e from V towards the image, and samples by distance along e; near
/// or inside the image (looking steeply down or up) they are indexed by angle
/// around V and samples by radius: polar form. Image coordinates are pixels,
/// x right, y down, pixel centres at +0.5.
struct PlaneLayout {
  double vx = 0, vy = 0;  // vertical vanishing point
  bool polar = false;
  bool wrap = false;         // polar over the whole circle (V inside the image)
  bool rise_outward = true;  // ray elevation grows moving away from V
  double ex = 0, ey = 1;     // axis unit vector (from V towards the image)
  double c0 = 0, dc = 1;     // column c has parameter c0 + (c + 0.5) dc (angle from e, or lambda)
  int columns = 0;
  double dr = 1;  // sample spacing along a column (pixels)
  /// Tiered polar layout: near V the fine columns lie far closer together
  /// than pixels, so there only every stride-th column is sampled. Column c
  /// carries samples from radius tier_start(c) outward; a pixel at sample
  /// radius kf interpolates between columns L and L + s, s = stride_at(kf), L
  /// a multiple of s. smax (a power of 2) is the coarsest stride; 1 = untiered.
  int smax = 1;
  /// Widest spacing of a tier's columns, in samples (dr): a tier ends where
  /// its columns would lie further apart.
  static constexpr double kTierSpacing = 0.7;

  /// The coarsest stride s (power of 2, <= smax) whose columns are at most
  /// kTierSpacing samples apart at radius kf: s kf dc <= kTierSpacing.
  int stride_at(double kf) const {
    if (smax == 1) return 1;
    const double t = kf * dc * (1.0 / kTierSpacing);
    if (t * smax <= 1.0) return smax;
    int s = 1;
    while (t * (2 * s) <= 1.0) s *= 2;
    return s;
  }
  /// First sample index column c needs: the inner edge of the finest tier
  /// that reads it (2 samples inside), 0 for columns of every tier.
  std::int64_t tier_start(int c) const;

  /// Sample k of column c is at V + k * dr * (wx, wy).
  void column_dir(int c, double& wx, double& wy) const { direction(c0 + (c + 0.5) * dc, wx, wy); }
  /// Direction of the image line with column parameter p (angle or lambda);
  /// it turns from e towards (-ey, ex) as p grows.
  void direction(double p, double& wx, double& wy) const;
  /// Fractional column and sample index of image point (x, y).
  void locate(double x, double y, double& cf, double& kf) const;
  /// Sample index range of column c covering the image (with a margin);
  /// returns false when the column misses the image.
  bool rows(int c, int width, int height, std::int64_t& k0, std::int64_t& k1) const;
};

/// Layout for `camera` rendering width x height pixels; `oversample` samples
/// per pixel along and across the planes (>= 0.25).
PlaneLayout make_plane_layout(const Camera& camera, int width, int height, double oversample);

}  // namespace terrasprite
