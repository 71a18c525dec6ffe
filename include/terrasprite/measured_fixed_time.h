// SPDX-License-Identifier: MIT
// The frame's work before the selection (with occlusion culling: the
// terrain drawn and its depth read back, which waits for the rasteriser),
// measured in each frame, made safe to budget the objects from.
#pragma once
#include <deque>

namespace terrasprite {

class MeasuredFixedTime {
 public:
  /// `window` frames of history (at least 1); `cap` (>= 1) x their median
  /// is the most a frame's measurement counts for.
  explicit MeasuredFixedTime(int window = 15, double cap = 1.5);

  /// Records `ms` and returns what to budget with: `ms`, capped at `cap` x
  /// the median of the last `window` measurements (this one included). A
  /// stall of the machine, not of the view, shows as one measurement far
  /// over the rest: uncapped, a 7.9 ms read-back against the usual 3.5
  /// left checkpoint B's objects 2 ms and its object SSIM fell from 0.95 to
  /// 0.50. A lasting change moves the median within window / 2 frames.
  /// Not positive or not finite: returns 0 (nothing measured) and records
  /// nothing.
  double accept(double ms);
  void reset() { recent_.clear(); }

 private:
  std::deque<double> recent_;
  int window_;
  double cap_;
};

}  // namespace terrasprite
