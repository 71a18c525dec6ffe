// SPDX-License-Identifier: MIT
// bench voxel's report: the voxel study's typed result in, JSON and a
// frame-time plot out.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "terrasprite/experiment/voxel.h"

namespace terrasprite::report {

/// The bench's JSON: device, terrain, size, path, frames, score_every,
/// scored_frames, pixel_voxel_ratio, reference, threads, default_variant,
/// variants, scaling_2v1, pitch_table, terrain_size_sweep and per_frame.
/// Figures not measured (no 1- and 2-thread pair) are null.
nlohmann::json voxel_bench_json(const VoxelBenchResult& r);

/// frame_times.dat (per frame: coherent and multires ms) and frame_times.gp
/// in `dir`, then gnuplot on it (frame_times.png). Returns "" or the
/// run_gnuplot failure line (the .dat is kept). Throws InputError when a
/// file cannot be written.
std::string write_voxel_plot(const VoxelBenchResult& r, const std::string& dir);

}  // namespace terrasprite::report
