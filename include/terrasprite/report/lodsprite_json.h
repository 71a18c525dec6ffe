// SPDX-License-Identifier: MIT
// The LOD-sprite study's JSON documents from its typed result: the one place
// their key names are spelled.
#pragma once
#include <nlohmann/json_fwd.hpp>

#include "terrasprite/experiment/lodsprite/lodsprite_result.h"

namespace terrasprite::report {

/// The `bench lodsprite` document (lodsprite.json, DESIGN.md's contract):
/// settings, per-renderer summaries, speed-up and bound, targets, sweeps,
/// figures, the optional cache / trigger / async parts and every frame.
nlohmann::json lodsprite_json(const lodsprite::LodspriteResult& r);

/// The demo's stats.json: the run's headline figures, its full / lod /
/// sprite / bound summaries (as in lodsprite.json) and a short row per frame.
nlohmann::json demo_stats_json(const lodsprite::LodspriteResult& r);

/// The `async_run` object: figures of both simulated displays, the targets,
/// the method.
nlohmann::json async_json(const lodsprite::AsyncComparison& c);

}  // namespace terrasprite::report
