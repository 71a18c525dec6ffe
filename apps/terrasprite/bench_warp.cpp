// SPDX-License-Identifier: MIT
// terrasprite bench warp: post-render warp quality and cost. Along each path
// every frame is rendered once, with a margin; frame b (every k_max+1-th) is
// a real frame, and frames b+1..b+k_max are warped from it by each method and
// scored against their own (cropped) render. Quality is computed outside the
// timed spans.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <thread>

#include "bench_commands.h"
#include "cli_common.h"
#include "terrasprite/report/plot.h"
#include "render_modes.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/experiment/flythrough.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/warp/warp.h"

namespace terrasprite::cli {
namespace {

struct BenchWarpOpts {
  TerrainOptions terrain;
  std::string renderer = "voxel";
  std::string size = "1920x1080";
  std::string path;  // empty: paper and low-fast
  int frames = 460;
  int k_max = 8;
  double margin = 0.05;
  int real_every = 4;
  std::string json;
  std::string out;
};

const WarpMethod kMethods[] = {WarpMethod::kPoly2, WarpMethod::kDepth};

// Scores of one warped frame against its true render, and what the camera did
// since the real frame (to say where a method breaks).
struct Score {
  double psnr, ssim, flip, psnr_masked, holes;
  int frame = 0, k = 0;
  double turn_deg = 0;     // angle between the real and the warped view direction
  double moved_m = 0;      // eye displacement since the real frame
  double clearance_m = 0;  // eye height above the ground below it
};

struct MethodRun {
  std::vector<double> warp_ms;
  std::vector<std::vector<Score>> by_k;  // [k - 1]
};

// How far camera `to` has turned and moved from `from`.
void describe_motion(const Camera& from, const Camera& to, const Heightfield& ground, Score& s) {
  const double c = std::clamp(glm::dot(from.forward(), to.forward()), -1.0, 1.0);
  s.turn_deg = glm::degrees(std::acos(c));
  s.moved_m = glm::length(to.position - from.position);
  s.clearance_m = to.position.z - ground.sample(to.position.x, to.position.y);
}

struct PathRun {
  std::string path;
  std::vector<double> real_ms;
  std::vector<MethodRun> methods;
};

double mean_of(const std::vector<double>& v) {
  return v.empty() ? NAN : mean(v);
}

Score score(const Frame& truth, const WarpedFrame& w) {
  std::vector<std::uint8_t> seen(w.holes.size());
  for (std::size_t i = 0; i < seen.size(); ++i) seen[i] = !w.holes[i];
  const ImageView a = truth.color.view(), b = w.frame.color.view();
  return {std::min(quality::psnr(a, b).rgb, 100.0), quality::ssim(a, b).ssim,
          quality::flip(a, b).mean, std::min(quality::psnr(a, b, seen).rgb, 100.0),
          w.hole_fraction};
}

PathRun run_path(const BenchWarpOpts& o, const std::string& spec, const Terrain& terrain,
                 Renderer& renderer, int w, int h, int mx, int my, Progress& progress) {
  PathRun run;
  run.path = spec;
  run.methods.resize(std::size(kMethods));
  for (auto& m : run.methods) m.by_k.resize(std::size_t(o.k_max));
  const std::vector<Camera> path = make_path(spec, terrain.heights, o.frames, double(w) / h);
  const int stride = o.k_max + 1;
  std::unique_ptr<Frame> real, previous;
  // One Warper per method, as a flythrough would hold: buffers reused.
  std::vector<Warper> warpers(std::size(kMethods));
  Warper crop;
  renderer.render(with_margin(path[0], w, h, mx, my), ReadBack::kColorDepth);  // warm-up
  for (int i = 0; i < int(path.size()); ++i) {
    Frame f = renderer.render(with_margin(path[i], w, h, mx, my), ReadBack::kColorDepth);
    run.real_ms.push_back(f.ms);
    const int k = i % stride;
    if (k == 0) {
      previous = std::move(real);
      real = std::make_unique<Frame>(std::move(f));
    } else {
      const Frame& truth = crop.warp(f, path[i], w, h, {WarpOptions{WarpMethod::kPoly2}}).frame;
      for (std::size_t m = 0; m < std::size(kMethods); ++m) {
        WarpOptions wo;
        wo.method = kMethods[m];
        const Frame* second = kMethods[m] == WarpMethod::kDepth ? previous.get() : nullptr;
        const WarpedFrame& wf = warpers[m].warp(*real, path[i], w, h, wo, second);
        run.methods[m].warp_ms.push_back(wf.frame.ms);
        Score sc = score(truth, wf);
        sc.frame = i;
        sc.k = k;
        describe_motion(path[std::size_t(i - k)], path[std::size_t(i)], terrain.heights, sc);
        run.methods[m].by_k[std::size_t(k - 1)].push_back(sc);
      }
    }
    progress(i + 1, int(path.size()));
  }
  return run;
}

nlohmann::json method_json(const PathRun& p, std::size_t m) {
  const MethodRun& r = p.methods[m];
  const double warp_ms = median(r.warp_ms), real_ms = median(p.real_ms);
  nlohmann::json by_k = nlohmann::json::array();
  for (std::size_t k = 0; k < r.by_k.size(); ++k) {
    const auto& s = r.by_k[k];
    if (s.empty()) continue;
    auto avg = [&](double Score::*f) {
      std::vector<double> v;
      for (const Score& x : s)
        if (std::isfinite(x.*f)) v.push_back(x.*f);
      return number_or_null(mean_of(v));
    };
    by_k.push_back({{"k", k + 1},
                    {"samples", s.size()},
                    {"psnr", avg(&Score::psnr)},
                    {"ssim", avg(&Score::ssim)},
                    {"flip", avg(&Score::flip)},
                    {"psnr_masked", avg(&Score::psnr_masked)},
                    {"hole_fraction", avg(&Score::holes)}});
  }
  // The worst-scoring warps (lowest PSNR), with the camera's motion: where
  // the method breaks (turns, parallax near the ground, disocclusions).
  std::vector<Score> all;
  for (const auto& s : r.by_k) all.insert(all.end(), s.begin(), s.end());
  const std::size_t shown = std::min<std::size_t>(all.size(), 5);
  std::partial_sort(all.begin(), all.begin() + std::ptrdiff_t(shown), all.end(),
                    [](const Score& a, const Score& b) { return a.psnr < b.psnr; });
  nlohmann::json worst = nlohmann::json::array();
  for (std::size_t i = 0; i < shown; ++i)
    worst.push_back({{"frame", all[i].frame},
                     {"k", all[i].k},
                     {"psnr", number_or_null(all[i].psnr)},
                     {"psnr_masked", number_or_null(all[i].psnr_masked)},
                     {"hole_fraction", number_or_null(all[i].holes)},
                     {"turn_deg", all[i].turn_deg},
                     {"moved_m", all[i].moved_m},
                     {"clearance_m", all[i].clearance_m}});
  return {{"name", to_string(kMethods[m])},
          {"path", p.path},
          {"worst", worst},
          {"warp_ms_median", number_or_null(warp_ms)},
          {"real_ms_median", number_or_null(real_ms)},
          {"cost_fraction", number_or_null(warp_ms / std::max(real_ms, 1e-9))},
          {"by_k", by_k}};
}

// The flythrough at 60 Hz output with every K-th frame real: the mean cost
// per output frame, (real + (K - 1) warps) / K, frames not overlapped.
nlohmann::json flythrough_json(const PathRun& p, std::size_t m, int K) {
  const double real = mean_of(p.real_ms), warp = mean_of(p.methods[m].warp_ms);
  return {{"path", p.path},
          {"method", to_string(kMethods[m])},
          {"real_every", K},
          {"real_ms_mean", number_or_null(real)},
          {"real_ms_p99", number_or_null(percentile(p.real_ms, 99))},
          {"warp_ms_mean", number_or_null(warp)},
          {"mean_ms_per_output_frame", number_or_null((real + (K - 1) * warp) / K)},
          {"meets_60hz", (real + (K - 1) * warp) / K <= 1000.0 / 60.0}};
}

void write_plot(const OutputDir& out, const std::vector<PathRun>& runs, int k_max) {
  std::ofstream dat(out.file("quality_vs_k.dat"));
  std::vector<std::string> titles;
  dat << "# k";
  for (const auto& p : runs)
    for (WarpMethod m : kMethods) {
      titles.push_back(fmt::format("{} {}", p.path, to_string(m)));
      dat << " psnr_" << p.path << "_" << to_string(m);
    }
  dat << '\n';
  for (int k = 1; k <= k_max; ++k) {
    dat << k;
    for (const auto& p : runs)
      for (const auto& m : p.methods) {
        double s = 0;
        for (const Score& x : m.by_k[std::size_t(k - 1)]) s += x.psnr;
        const auto n = m.by_k[std::size_t(k - 1)].size();
        dat << ' ' << (n ? s / double(n) : NAN);
      }
    dat << '\n';
  }
  dat.close();
  std::ofstream gp(out.file("quality_vs_k.gp"));
  gp << "set terminal pngcairo size 900,500\nset output 'quality_vs_k.png'\n"
     << "set xlabel 'K: output frames since the last real frame'\nset ylabel 'PSNR (dB) vs "
        "true render'\nset key top right\nset grid\nplot ";
  for (std::size_t c = 0; c < titles.size(); ++c)
    gp << (c ? ", " : "") << "'quality_vs_k.dat' using 1:" << c + 2 << " with linespoints title '"
       << titles[c] << "'";
  gp << '\n';
  gp.close();
  const std::string error = run_gnuplot(out.partial().string(), "quality_vs_k.gp");
  if (!error.empty())
    fmt::print(stderr, "warning: {}; quality_vs_k.dat kept without a plot\n", error);
}

void run(const BenchWarpOpts& o) {
  auto [w, h] = parse_size(o.size, "--size");
  if (o.frames < 2 || o.frames > 100000)
    throw InputError(fmt::format("--frames {}: must be between 2 and 100000", o.frames));
  if (o.k_max < 1 || o.k_max > 64)
    throw InputError(fmt::format("--k-max {}: must be within 1..64", o.k_max));
  if (o.real_every < 1 || o.real_every > 64)
    throw InputError(fmt::format("--real-every {}: must be within 1..64", o.real_every));
  if (!(o.margin >= 0 && o.margin <= 1))
    throw InputError(fmt::format("--margin {}: must be within 0..1", o.margin));
  if (o.renderer != "voxel" && o.renderer != "full")
    throw InputError(fmt::format("--renderer {}: expected voxel or full", o.renderer));
  const std::vector<std::string> specs =
      o.path.empty() ? std::vector<std::string>{"paper", "low-fast"} : std::vector{o.path};
  const std::string out_dir = o.out.empty() ? std::string("out/bench_warp") : o.out;
  check_outputs(out_dir, {o.json});
  Terrain terrain = load_terrain_verbose(o.terrain);
  for (const auto& s : specs) make_path(s, terrain.heights, 1, double(w) / h);  // validate early
  const int mx = int(std::lround(o.margin * w)), my = int(std::lround(o.margin * h));
  RenderStack stack = make_render_stack(o.renderer, terrain, w + 2 * mx, h + 2 * my, 16);
  OutputDir out(out_dir, output_policy());

  std::vector<PathRun> runs;
  Progress progress("bench warp");
  for (const auto& s : specs)
    runs.push_back(run_path(o, s, terrain, *stack.renderer, w, h, mx, my, progress));

  nlohmann::json methods = nlohmann::json::array(), fly = nlohmann::json::array();
  for (const auto& p : runs)
    for (std::size_t m = 0; m < std::size(kMethods); ++m) {
      methods.push_back(method_json(p, m));
      fly.push_back(flythrough_json(p, m, o.real_every));
    }
  write_plot(out, runs, o.k_max);
  nlohmann::json j = {
      {"device",
       fmt::format("{} ({} hardware threads)", stack.device, std::thread::hardware_concurrency())},
      {"terrain", terrain_json(terrain)},
      {"size", {w, h}},
      {"renderer", o.renderer},
      {"path", specs},
      {"frames", o.frames},
      {"k_max", o.k_max},
      {"margin_px", {mx, my}},
      {"methods", methods},
      {"flythrough", fly},
      {"note",
       "real frames are rendered with the margin; each method warps real frame b to frames "
       "b+1..b+k_max and is scored against their cropped renders; flythrough figures assume "
       "frames do not overlap"}};
  write_json(j, out.file("bench_warp.json"));  // JSON last: the directory is complete
  out.commit();
  if (!o.json.empty()) write_json(j, o.json);
  fmt::print("{}\n", j.dump(2));
}

}  // namespace

void add_bench_warp(CLI::App& bench) {
  auto* cmd = bench.add_subcommand("warp", "post-render warp quality and cost against real frames");
  auto o = std::make_shared<BenchWarpOpts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--renderer", o->renderer, "renderer of the real frames: voxel (default) or full")
      ->check(CLI::IsMember({"voxel", "full"}));
  cmd->add_option("--size", o->size, "output image size WxH (default 1920x1080)");
  cmd->add_option("--path", o->path,
                  "'paper', 'low-fast' or a JSON path file (default: both shipped)");
  cmd->add_option("--frames", o->frames, "frames along each path (default 460)");
  cmd->add_option("--k-max", o->k_max, "warp up to this many frames past a real one (default 8)");
  cmd->add_option("--margin", o->margin,
                  "real frames drawn this fraction wider on each side (default 0.05)");
  cmd->add_option(
      "--real-every", o->real_every,
      "K for the flythrough cost figure: one real frame per K output frames (default 4)");
  cmd->add_option("--json", o->json, "also write the JSON here");
  cmd->add_option("--out", o->out, "output directory: plot, JSON (default out/bench_warp)");
  cmd->callback([o] { run(*o); });
}

}  // namespace terrasprite::cli
