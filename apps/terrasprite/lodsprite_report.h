// SPDX-License-Identifier: MIT
// The LOD-sprite report: gnuplot plots of the paper's Figs. 8-12 from our
// data, and an index.html with the numbers and the Figs. 13-14 images.
#pragma once
#include "lodsprite_result.h"
#include "terrasprite/output/output_dir.h"

namespace terrasprite::cli {

/// Writes the .dat/.gp files, runs gnuplot (plots are skipped, and the page
/// says so, when gnuplot is missing or fails), and writes index.html from a
/// run_lodsprite() result. The figure PNGs must already be in `out`.
void write_lodsprite_report(const LodspriteResult& r, OutputDir& out);

}  // namespace terrasprite::cli
