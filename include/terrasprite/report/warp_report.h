// SPDX-License-Identifier: MIT
// bench warp's report: the warp study's typed result in, JSON and a
// quality-by-k plot out.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "terrasprite/experiment/warp.h"

namespace terrasprite::report {

/// The bench's JSON: device, terrain, size, renderer, path, frames, k_max,
/// margin_px, methods (per path and method: worst warps, medians,
/// cost_fraction, by_k), flythrough and a note on the method. Figures not
/// measured are null.
nlohmann::json warp_bench_json(const WarpBenchResult& r);

/// quality_vs_k.dat (per k, the mean PSNR of every path and method) and
/// quality_vs_k.gp in `dir`, then gnuplot on it (quality_vs_k.png). Returns
/// "" or the run_gnuplot failure line (the .dat is kept). Throws InputError
/// when a file cannot be written.
std::string write_warp_plot(const WarpBenchResult& r, const std::string& dir);

}  // namespace terrasprite::report
