// SPDX-License-Identifier: MIT
// The frame's work before the selection (with occlusion culling: the
// terrain drawn and its depth read back, which waits for the rasteriser),
// measured in each frame: how far it is from usual is known before the
// selection, and is taken off (or added to) that frame's object budget.
#pragma once
#include <deque>

namespace terrasprite {

class MeasuredFixedTime {
 public:
  /// `window` frames of history (at least 1); a deviation counts for at
  /// most `cap` (>= 0) x the median.
  explicit MeasuredFixedTime(int window = 15, double cap = 0.5);

  /// Records `ms` and returns its deviation from the median of the last
  /// `window` measurements (this one included), clamped to +-`cap` x that
  /// median. The median is the usual cost, which the cost model's frame
  /// term already holds; the deviation is this frame's known surprise. A
  /// stall of the machine, not of the view, shows as one measurement far
  /// over the rest: taken whole it would leave the objects less than their
  /// cheapest for that frame. A lasting change moves the median within
  /// window / 2 frames. Not positive or not finite: 0, recorded nothing.
  double deviation(double ms);
  /// log(ms / usual) of the last deviation() call, from its clamped
  /// deviation (so within log(1 -+ cap)); 0 before any.
  double last_log_ratio() const { return last_log_ratio_; }
  void reset() {
    recent_.clear();
    last_log_ratio_ = 0;
  }

 private:
  std::deque<double> recent_;
  int window_;
  double cap_;
  double last_log_ratio_ = 0;
};

}  // namespace terrasprite
