// SPDX-License-Identifier: MIT
// Hysteresis on per-instance representation choices: an instance that
// switched recently keeps its representation unless the budget forbids it,
// so nothing flips back and forth frame to frame.
#pragma once
#include <span>
#include <unordered_map>

#include "terrasprite/hybrid/representation_selection.h"

namespace terrasprite {

struct HysteresisOptions {
  /// An instance switches at most once in this many frames (unless the
  /// budget forces it to a cheaper representation, or see `max_hold_loss`).
  int hold_frames = 8;
  /// A switch whose benefit gain is under this fraction of the instance's
  /// benefit is not worth a visible pop: the old choice stays.
  double min_gain = 0.01;
  /// The hold never costs an instance more than this fraction of the
  /// benefit the selection wants for it: a switch that soon gains more goes
  /// through: after a sudden cut in the budget (every instance at its
  /// cheapest), a plain hold of `hold_frames` would keep the cheapest
  /// representations after the budget recovered and the instances came
  /// closer.
  double max_hold_loss = 0.05;
};

class SelectionHysteresis {
 public:
  explicit SelectionHysteresis(const HysteresisOptions& options = {}) : options_(options) {}

  /// Reverts switches in `selection` (over `instances`, this frame's options)
  /// that gain too little, or come too soon and gain under `max_hold_loss`
  /// (a switch to a cheaper representation always counts as too little
  /// gain when it comes soon), cheapest reverts first, as long
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
