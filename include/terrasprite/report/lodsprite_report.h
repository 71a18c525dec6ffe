// SPDX-License-Identifier: MIT
// The LOD-sprite report: gnuplot plots of the paper's Figs. 8-12 from our
// data, the Figs. 13-14 images, and an index.html that opens with the
// flight's video and carries the numbers.
#pragma once
#include <string>

#include "terrasprite/experiment/lodsprite/lodsprite_result.h"
#include "terrasprite/output/output_dir.h"

namespace terrasprite::report {

/// Writes the same-frame figure PNGs, the .dat/.gp files, runs gnuplot
/// (plots are skipped, and the page says so, when gnuplot is missing or
/// fails) and writes index.html into `out` from a run_lodsprite() result.
/// The JSON documents are lodsprite_json.h's. Unwritable files: InputError.
void write_lodsprite_report(const lodsprite::LodspriteResult& r, OutputDir& out);

/// A few lines for the console: the terrain's grid (resampled or as given),
/// keyframes by trigger, the speed-up and the targets (n/a where not meaningful).
std::string lodsprite_summary_text(const lodsprite::LodspriteResult& r);

}  // namespace terrasprite::report
