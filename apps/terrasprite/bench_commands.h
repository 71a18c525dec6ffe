// SPDX-License-Identifier: MIT
// The benchmarks under `terrasprite bench`, one file each.
#pragma once
#include <CLI/CLI.hpp>

namespace terrasprite::cli {

/// bench render: full resolution against plain LOD on one path (median ms).
void add_bench_render(CLI::App& bench);
/// bench voxel: the CPU ray caster per variant, thread scaling, quality vs reference.
void add_bench_voxel(CLI::App& bench);
/// bench lodsprite: the LOD-sprite paper's reproduction.
void add_bench_lodsprite(CLI::App& bench);
/// bench warp: post-render warp quality (vs true renders) and cost per method.
void add_bench_warp(CLI::App& bench);
/// bench stream: a flythrough over a tiled terrain streamed from disk vs in memory.
void add_bench_stream(CLI::App& bench);
/// bench hybrid: objects under a frame-time budget, the hybrid-objects walkthrough.
void add_bench_hybrid(CLI::App& bench);
/// bench replay-controller: the budget controller replayed on recorded bench hybrid runs.
void add_bench_replay_controller(CLI::App& bench);

}  // namespace terrasprite::cli
