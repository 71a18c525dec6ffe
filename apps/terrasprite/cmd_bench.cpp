// SPDX-License-Identifier: MIT
// terrasprite bench: whole-system benchmarks, each a sub-command printing JSON.
#include "bench_commands.h"
#include "commands.h"

namespace terrasprite::cli {

void add_bench(CLI::App& app, const OutputPolicy& policy) {
  auto* bench = app.add_subcommand("bench", "whole-system benchmarks (JSON + plots)");
  bench->require_subcommand(1);
  add_bench_render(*bench, policy);
  add_bench_voxel(*bench, policy);
  add_bench_lodsprite(*bench, policy);
  add_bench_warp(*bench, policy);
  add_bench_stream(*bench, policy);
  add_bench_hybrid(*bench, policy);
  add_bench_replay_controller(*bench, policy);
}

}  // namespace terrasprite::cli
