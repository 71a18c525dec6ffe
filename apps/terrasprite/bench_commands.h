// SPDX-License-Identifier: MIT
// The benchmarks under `terrasprite bench`, one file each; `policy` as in commands.h.
#pragma once
#include <CLI/CLI.hpp>

#include "terrasprite/output/output_file.h"

namespace terrasprite::cli {

/// bench render: full resolution against plain LOD on one path (median ms).
void add_bench_render(CLI::App& bench, const OutputPolicy& policy);
/// bench voxel: the CPU ray caster per variant, thread scaling, quality vs reference.
void add_bench_voxel(CLI::App& bench, const OutputPolicy& policy);
/// bench lodsprite: the LOD-sprite paper's reproduction.
void add_bench_lodsprite(CLI::App& bench, const OutputPolicy& policy);
/// bench warp: post-render warp quality (vs true renders) and cost per method.
void add_bench_warp(CLI::App& bench, const OutputPolicy& policy);
/// bench stream: a flythrough over a tiled terrain streamed from disk vs in memory.
void add_bench_stream(CLI::App& bench, const OutputPolicy& policy);
/// bench hybrid: objects under a frame-time budget, the hybrid-objects walkthrough.
void add_bench_hybrid(CLI::App& bench, const OutputPolicy& policy);
/// bench replay-controller: the budget controller replayed on recorded bench hybrid runs.
void add_bench_replay_controller(CLI::App& bench, const OutputPolicy& policy);

}  // namespace terrasprite::cli
