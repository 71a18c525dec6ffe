// SPDX-License-Identifier: MIT
// terrasprite bench: whole-system benchmarks, each a sub-command printing JSON.
#include "bench_commands.h"
#include "commands.h"

namespace terrasprite::cli {

void add_bench(CLI::App& app) {
  auto* bench = app.add_subcommand("bench", "whole-system benchmarks (JSON + plots)");
  bench->require_subcommand(1);
  add_bench_render(*bench);
  add_bench_voxel(*bench);
  add_bench_lodsprite(*bench);
  add_bench_warp(*bench);
  add_bench_stream(*bench);
  add_bench_hybrid(*bench);
  add_bench_replay_controller(*bench);
}

}  // namespace terrasprite::cli
