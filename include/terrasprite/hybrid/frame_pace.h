// SPDX-License-Identifier: MIT
// The machine's pace in one frame. With occlusion culling the terrain is
// drawn and its depth read back before the selection, so how much longer
// (or shorter) than usual that took is known before the objects are
// chosen. Its deviation is already added to the frame's prediction as
// milliseconds (MeasuredFixedTime); what follows the read-back runs slow or
// fast with it too (the same machine pace on the objects' draws). This
// learns that slope, d log(measured / predicted) per unit of
// log(read-back / its median), from the frames themselves and turns each
// frame's deviation into a factor on the part of the frame's prediction that
// follows the read-back. Figures: docs/results/2026-12-07-hybrid-frame-pace.md.
#pragma once
#include <deque>
#include <utility>

namespace terrasprite {

struct FramePaceOptions {
  int window = 60;  ///< frames the slope is fitted over
  /// Shrinks the slope towards 0 (no pace): as if this many frames whose
  /// read-back deviated by a typical 0.1 (log) had shown no pace at all.
  double prior_frames = 20;
  double max_slope = 1;  ///< the slope is fitted within [0, max_slope]
  int min_frames = 8;    ///< fewer frames in: slope 0
};

class FramePace {
 public:
  explicit FramePace(const FramePaceOptions& options = {});

  /// Records one frame: x = z s, z = log(read-back ms / its usual) and s
  /// the share of the frame's prediction that follows the read-back (by
  /// how much the whole frame's log moves when that part runs exp(z) x as
  /// long), and the frame's log(measured / predicted without the pace).
  /// Non-finite values are ignored.
  void observe(double x, double log_residual);
  /// The fitted slope (d log frame / d x), in [0, max_slope].
  double slope() const;
  /// exp(slope() z): the factor on the part of the frame's prediction that
  /// follows a read-back with log(ms / usual) = z.
  double factor(double z) const;
  void reset() { frames_.clear(); }

 private:
  FramePaceOptions o_;
  std::deque<std::pair<double, double>> frames_;  ///< (x, residual), newest last
};

}  // namespace terrasprite
