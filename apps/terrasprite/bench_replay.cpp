// SPDX-License-Identifier: MIT
// `terrasprite bench replay-controller`: the budget controller replayed on
// recorded `bench hybrid` runs (experiment/hybrid/controller_replay_run.h),
// its table printed and its JSON written.
#include <fmt/format.h>

#include <memory>

#include "bench_commands.h"
#include "cli_common.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/hybrid/controller_replay_run.h"
#include "terrasprite/report/hybrid_report.h"
#include "terrasprite/report/json_writer.h"

namespace terrasprite::cli {
namespace {

struct ReplayCommand {
  ControllerReplayOptions o;
  std::string scenarios = "pm,mixed-optimal", json;
};

std::vector<WalkScenario> scenarios(const std::string& text) {
  std::vector<WalkScenario> out;
  for (const std::string& name : split_list(text)) {
    const std::optional<WalkScenario> s = parse_walk_scenario(name);
    if (!s)
      throw InputError(fmt::format(
          "--scenarios: '{}' is not full, ibr, pm, mixed, mixed-optimal or full-culled", name));
    out.push_back(*s);
  }
  return out;
}

void run_replay(ReplayCommand& c, const OutputPolicy& policy) {
  if (c.o.runs.empty()) throw InputError("replay-controller: name at least one run directory");
  if (!c.json.empty()) check_outputs(policy, "", {c.json});
  c.o.scenarios = scenarios(c.scenarios);
  const ControllerReplayResult r = run_controller_replay(c.o);
  fmt::print("{}", report::controller_replay_table(r));
  if (!c.json.empty()) report::write_json(report::controller_replay_json(r), c.json, policy);
}

}  // namespace

void add_bench_replay_controller(CLI::App& bench, const OutputPolicy& policy) {
  auto* cmd = bench.add_subcommand(
      "replay-controller",
      "the budget controller replayed on recorded bench hybrid runs (their frames_*.dat), with "
      "its options changed: p95 and budget against the target, recorded and replayed");
  auto c = std::make_shared<ReplayCommand>();
  ControllerReplayOptions* a = &c->o;
  cmd->add_option("runs", a->runs, "bench hybrid output directories (hybrid.json, frames_*.dat)")
      ->required();
  cmd->add_option("--scenarios", c->scenarios, "which scenarios' frames")->capture_default_str();
  cmd->add_option("--tolerance", a->controller.tolerance, "the p95's aim, x target")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 2.0));
  cmd->add_option("--margin", a->controller.quantile_margin,
                  "standard errors of the sample p95 added to it")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--centre-half-width", a->controller.centre_half_width,
                  "frames each side of the running median the spread is taken about")
      ->capture_default_str()
      ->check(CLI::Range(1, 50));
  cmd->add_option("--prior-noise", a->controller.prior_noise,
                  "frame noise (sigma, log) assumed until three frames are in")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 2.0));
  cmd->add_option("--quantile-window", a->controller.quantile_window, "frames in the p95's window")
      ->capture_default_str()
      ->check(CLI::Range(4, 10000));
  cmd->add_option("--quantile-min-frames", a->controller.quantile_min_frames,
                  "frames of spread in before the p95 window sets the aim (at most the window)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--drift", a->controller.drift,
                  "how far the measured / predicted ratio is taken to move per frame (sigma, "
                  "log): sets how fast the ratio follows the frames")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--json", c->json, "also write the figures as JSON");
  cmd->callback([c, &policy] { run_replay(*c, policy); });
}

}  // namespace terrasprite::cli
