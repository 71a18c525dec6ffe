// SPDX-License-Identifier: MIT
// The warp study (terrasprite/experiment/warp.h): each path flown once with
// the margin, warps scored by k, then the per-method and flythrough figures.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <thread>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/experiment/render_stack.h"
#include "terrasprite/experiment/warp.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite {
namespace {

constexpr std::size_t kMethods = kWarpBenchMethods.size();

// How far camera `to` has turned and moved from `from`.
void describe_motion(const Camera& from, const Camera& to, const Heightfield& ground,
                     WarpScore& s) {
  const double c = std::clamp(glm::dot(from.forward(), to.forward()), -1.0, 1.0);
  s.turn_deg = glm::degrees(std::acos(c));
  s.moved_m = glm::length(to.position - from.position);
  s.clearance_m = to.position.z - ground.sample(to.position.x, to.position.y);
}

double mean_of(const std::vector<double>& v) {
  return v.empty() ? NAN : mean(v);
}

WarpScore score(const Frame& truth, const WarpedFrame& w) {
  std::vector<std::uint8_t> seen(w.holes.size());
  for (std::size_t i = 0; i < seen.size(); ++i) seen[i] = !w.holes[i];
  const ImageView a = truth.color.view(), b = w.frame.color.view();
  WarpScore s;
  s.psnr = std::min(quality::psnr(a, b).rgb, 100.0);
  s.ssim = quality::ssim(a, b).ssim;
  s.flip = quality::flip(a, b).mean;
  s.psnr_masked = std::min(quality::psnr(a, b, seen).rgb, 100.0);
  s.holes = w.hole_fraction;
  return s;
}

struct Geometry {
  int w, h, mx, my;
};

// Frame i of the path: real when i % (k_max + 1) == 0, else warped from the
// last real frame by each method and scored against its own cropped render.
WarpPathRun run_path(const WarpBenchOptions& o, const std::string& spec, const Terrain& terrain,
                     Renderer& renderer, const Geometry& g) {
  WarpPathRun run;
  run.path = spec;
  for (WarpMethod m : kWarpBenchMethods)
    run.methods.push_back({m, {}, std::vector<std::vector<WarpScore>>(std::size_t(o.k_max))});
  const std::vector<Camera> path =
      make_path(spec, terrain.heights, o.frames, double(g.w) / g.h);
  const int stride = o.k_max + 1;
  std::unique_ptr<Frame> real, previous;
  // One Warper per method, as a flythrough would hold: buffers reused.
  std::vector<Warper> warpers(kMethods);
  Warper crop;
  renderer.render(with_margin(path[0], g.w, g.h, g.mx, g.my), ReadBack::kColorDepth);  // warm-up
  for (int i = 0; i < int(path.size()); ++i) {
    Frame f = renderer.render(with_margin(path[i], g.w, g.h, g.mx, g.my), ReadBack::kColorDepth);
    run.real_ms.push_back(f.ms);
    const int k = i % stride;
    if (k == 0) {
      previous = std::move(real);
      real = std::make_unique<Frame>(std::move(f));
    } else {
      const Frame& truth =
          crop.warp(f, path[i], g.w, g.h, {WarpOptions{WarpMethod::kPoly2}}).frame;
      for (std::size_t m = 0; m < kMethods; ++m) {
        WarpOptions wo;
        wo.method = kWarpBenchMethods[m];
        const Frame* second = wo.method == WarpMethod::kDepth ? previous.get() : nullptr;
        const WarpedFrame& wf = warpers[m].warp(*real, path[i], g.w, g.h, wo, second);
        run.methods[m].warp_ms.push_back(wf.frame.ms);
        WarpScore sc = score(truth, wf);
        sc.frame = i;
        sc.k = k;
        describe_motion(path[std::size_t(i - k)], path[std::size_t(i)], terrain.heights, sc);
        run.methods[m].by_k[std::size_t(k - 1)].push_back(sc);
      }
    }
    if (o.progress) o.progress(i + 1, int(path.size()));
  }
  return run;
}

WarpKSummary k_summary(int k, const std::vector<WarpScore>& s) {
  auto avg = [&](double WarpScore::*f) {
    std::vector<double> v;
    for (const WarpScore& x : s)
      if (std::isfinite(x.*f)) v.push_back(x.*f);
    return mean_of(v);
  };
  return {k,
          int(s.size()),
          avg(&WarpScore::psnr),
          avg(&WarpScore::ssim),
          avg(&WarpScore::flip),
          avg(&WarpScore::psnr_masked),
          avg(&WarpScore::holes)};
}

WarpMethodSummary method_summary(const WarpPathRun& p, std::size_t m) {
  const WarpMethodRun& r = p.methods[m];
  WarpMethodSummary out;
  out.method = r.method;
  out.path = p.path;
  out.warp_ms_median = median(r.warp_ms);
  out.real_ms_median = median(p.real_ms);
  out.cost_fraction = out.warp_ms_median / std::max(out.real_ms_median, 1e-9);
  for (std::size_t k = 0; k < r.by_k.size(); ++k)
    if (!r.by_k[k].empty()) out.by_k.push_back(k_summary(int(k + 1), r.by_k[k]));
  // The worst-scoring warps (lowest PSNR), with the camera's motion: where
  // the method breaks (turns, parallax near the ground, disocclusions).
  std::vector<WarpScore> all;
  for (const auto& s : r.by_k) all.insert(all.end(), s.begin(), s.end());
  const std::size_t shown = std::min<std::size_t>(all.size(), 5);
  std::partial_sort(all.begin(), all.begin() + std::ptrdiff_t(shown), all.end(),
                    [](const WarpScore& a, const WarpScore& b) { return a.psnr < b.psnr; });
  out.worst.assign(all.begin(), all.begin() + std::ptrdiff_t(shown));
  return out;
}

WarpFlythrough flythrough(const WarpPathRun& p, std::size_t m, int K) {
  WarpFlythrough f;
  f.path = p.path;
  f.method = p.methods[m].method;
  f.real_every = K;
  f.real_ms_mean = mean_of(p.real_ms);
  f.real_ms_p99 = percentile(p.real_ms, 99);
  f.warp_ms_mean = mean_of(p.methods[m].warp_ms);
  f.mean_ms_per_output_frame = (f.real_ms_mean + (K - 1) * f.warp_ms_mean) / K;
  f.meets_60hz = f.mean_ms_per_output_frame <= 1000.0 / 60.0;
  return f;
}

}  // namespace

WarpBenchResult run_warp_bench(const Terrain& terrain, const WarpBenchOptions& o) {
  const double aspect = double(o.width) / o.height;
  for (const auto& s : o.paths) make_path(s, terrain.heights, 1, aspect);  // before any frame
  const Geometry g{o.width, o.height, int(std::lround(o.margin * o.width)),
                   int(std::lround(o.margin * o.height))};
  RenderStackOptions so;
  so.mode = o.renderer;
  so.width = g.w + 2 * g.mx;
  so.height = g.h + 2 * g.my;
  so.lod_quads = 16;
  RenderStack stack = make_render_stack(terrain, so);

  WarpBenchResult res;
  res.device = fmt::format("{} ({} hardware threads)", stack.device,
                           std::thread::hardware_concurrency());
  res.terrain = terrain_info(terrain);
  res.width = o.width;
  res.height = o.height;
  res.renderer = o.renderer;
  res.paths = o.paths;
  res.frames = o.frames;
  res.k_max = o.k_max;
  res.margin_x = g.mx;
  res.margin_y = g.my;
  for (const auto& s : o.paths) res.runs.push_back(run_path(o, s, terrain, stack.renderer(), g));
  for (const WarpPathRun& p : res.runs)
    for (std::size_t m = 0; m < kMethods; ++m) {
      res.methods.push_back(method_summary(p, m));
      res.flythrough.push_back(flythrough(p, m, o.real_every));
    }
  return res;
}

}  // namespace terrasprite
