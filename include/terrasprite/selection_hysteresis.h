// SPDX-License-Identifier: MIT
// Hysteresis on per-instance representation choices: an instance that
// switched recently keeps its representation unless the budget forbids it,
// so nothing flips back and forth frame to frame.
#pragma once
#include <span>
#include <unordered_map>

#include "terrasprite/representation_selection.h"

namespace terrasprite {

struct HysteresisOptions {
  /// An instance switches at most once in this many frames (unless the
  /// budget forces it to a cheaper representation).
  int hold_frames = 8;
  /// A switch whose benefit gain is under this fraction of the instance's
  /// benefit is not worth a visible pop: the old choice stays.
  double min_gain = 0.01;
};

class SelectionHysteresis {
 public:
  explicit SelectionHysteresis(const HysteresisOptions& options = {}) : options_(options) {}

  /// Reverts switches in `selection` (over `instances`, this frame's options)
  /// that come too soon or gain too little, cheapest reverts first, as long
  /// as the total expected cost stays within `budget_ms` (or does not grow,
  /// when the selection is already over it). Returns the switches kept this
  /// frame (instances seen last frame whose representation changed).
  int apply(std::span<const InstanceOptions> instances, FrameSelection& selection,
            double budget_ms);
  void reset() { last_.clear(); }

 private:
  struct Last {
    Representation rep;
    int frame_switched = -1000000;
  };
  HysteresisOptions options_;
  std::unordered_map<int, Last> last_;
  int frame_ = 0;
};

}  // namespace terrasprite
