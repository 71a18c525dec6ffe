// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/selection_hysteresis.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace terrasprite {
namespace {

bool same(const Representation& a, const Representation& b) {
  return a.kind == b.kind &&
         (a.kind == ObjectKind::kMesh ? a.level == b.level
                                      : a.resolution == b.resolution && a.views == b.views);
}

int find_option(const InstanceOptions& inst, const Representation& rep) {
  for (std::size_t o = 0; o < inst.options.size(); ++o)
    if (same(inst.options[o].rep, rep)) return int(o);
  return -1;
}

}  // namespace

int SelectionHysteresis::apply(std::span<const InstanceOptions> instances,
                               FrameSelection& selection, double budget_ms) {
  struct Revert {
    std::size_t i;
    int option;
    double extra_ms;
  };
  std::vector<Revert> reverts;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const auto it = last_.find(instances[i].instance);
    if (it == last_.end()) continue;
    const int old = find_option(instances[i], it->second.rep);
    const int now = selection.option[i];
    if (old < 0 || old == now) continue;
    const RepresentationOption& a = instances[i].options[std::size_t(old)];
    const RepresentationOption& b = instances[i].options[std::size_t(now)];
    const double gain = benefit(instances[i], b) - benefit(instances[i], a);
    const bool too_soon = frame_ - it->second.frame_switched < options_.hold_frames &&
                          gain <= options_.max_hold_loss * benefit(instances[i], b);
    const bool too_small =
        std::abs(gain) <= options_.min_gain * std::max(benefit(instances[i], a), 1e-12);
    if (too_soon || too_small) reverts.push_back({i, old, a.cost_ms - b.cost_ms});
  }
  std::sort(reverts.begin(), reverts.end(),
            [](const Revert& a, const Revert& b) { return a.extra_ms < b.extra_ms; });
  const double limit = std::max(budget_ms, selection.cost_ms);
  for (const Revert& r : reverts) {
    if (selection.cost_ms + r.extra_ms > limit) continue;
    const RepresentationOption& a = instances[r.i].options[std::size_t(r.option)];
    const RepresentationOption& b = instances[r.i].options[std::size_t(selection.option[r.i])];
    selection.cost_ms += r.extra_ms;
    selection.benefit += benefit(instances[r.i], a) - benefit(instances[r.i], b);
    selection.option[r.i] = r.option;
  }
  int switches = 0;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const Representation& rep = instances[i].options[std::size_t(selection.option[i])].rep;
    auto [it, fresh] = last_.try_emplace(instances[i].instance, Last{rep, -1000000});
    if (!fresh && !same(it->second.rep, rep)) {
      it->second = {rep, frame_};
      ++switches;
    }
  }
  ++frame_;
  return switches;
}

}  // namespace terrasprite
