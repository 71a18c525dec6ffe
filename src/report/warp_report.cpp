// SPDX-License-Identifier: MIT
#include "terrasprite/report/warp_report.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/report/terrain_json.h"

namespace terrasprite::report {
namespace {

nlohmann::json worst_json(const WarpScore& s) {
  return {{"frame", s.frame},
          {"k", s.k},
          {"psnr", number_or_null(s.psnr)},
          {"psnr_masked", number_or_null(s.psnr_masked)},
          {"hole_fraction", number_or_null(s.holes)},
          {"turn_deg", s.turn_deg},
          {"moved_m", s.moved_m},
          {"clearance_m", s.clearance_m}};
}

nlohmann::json method_json(const WarpMethodSummary& m) {
  nlohmann::json by_k = nlohmann::json::array();
  for (const WarpKSummary& k : m.by_k)
    by_k.push_back({{"k", k.k},
                    {"samples", k.samples},
                    {"psnr", number_or_null(k.psnr)},
                    {"ssim", number_or_null(k.ssim)},
                    {"flip", number_or_null(k.flip)},
                    {"psnr_masked", number_or_null(k.psnr_masked)},
                    {"hole_fraction", number_or_null(k.hole_fraction)}});
  nlohmann::json worst = nlohmann::json::array();
  for (const WarpScore& s : m.worst) worst.push_back(worst_json(s));
  return {{"name", to_string(m.method)},
          {"path", m.path},
          {"worst", worst},
          {"warp_ms_median", number_or_null(m.warp_ms_median)},
          {"real_ms_median", number_or_null(m.real_ms_median)},
          {"cost_fraction", number_or_null(m.cost_fraction)},
          {"by_k", by_k}};
}

nlohmann::json flythrough_json(const WarpFlythrough& f) {
  return {{"path", f.path},
          {"method", to_string(f.method)},
          {"real_every", f.real_every},
          {"real_ms_mean", number_or_null(f.real_ms_mean)},
          {"real_ms_p99", number_or_null(f.real_ms_p99)},
          {"warp_ms_mean", number_or_null(f.warp_ms_mean)},
          {"mean_ms_per_output_frame", number_or_null(f.mean_ms_per_output_frame)},
          {"meets_60hz", f.meets_60hz}};
}

}  // namespace

nlohmann::json warp_bench_json(const WarpBenchResult& r) {
  nlohmann::json methods = nlohmann::json::array(), fly = nlohmann::json::array();
  for (const WarpMethodSummary& m : r.methods) methods.push_back(method_json(m));
  for (const WarpFlythrough& f : r.flythrough) fly.push_back(flythrough_json(f));
  return {
      {"device", r.device},
      {"terrain", terrain_json(r.terrain)},
      {"size", {r.width, r.height}},
      {"renderer", to_string(r.renderer)},
      {"path", r.paths},
      {"frames", r.frames},
      {"k_max", r.k_max},
      {"margin_px", {r.margin_x, r.margin_y}},
      {"methods", methods},
      {"flythrough", fly},
      {"note",
       "real frames are rendered with the margin; each method warps real frame b to frames "
       "b+1..b+k_max and is scored against their cropped renders; flythrough figures assume "
       "frames do not overlap"}};
}

std::string write_warp_plot(const WarpBenchResult& r, const std::string& dir) {
  std::ostringstream dat;
  std::vector<std::string> titles;
  dat << "# k";
  for (const WarpPathRun& p : r.runs)
    for (const WarpMethodRun& m : p.methods) {
      titles.push_back(fmt::format("{} {}", p.path, to_string(m.method)));
      dat << " psnr_" << p.path << "_" << to_string(m.method);
    }
  dat << '\n';
  for (int k = 1; k <= r.k_max; ++k) {
    dat << k;
    for (const WarpPathRun& p : r.runs)
      for (const WarpMethodRun& m : p.methods) {
        double s = 0;
        for (const WarpScore& x : m.by_k[std::size_t(k - 1)]) s += x.psnr;
        const auto n = m.by_k[std::size_t(k - 1)].size();
        dat << ' ' << (n ? s / double(n) : NAN);
      }
    dat << '\n';
  }
  write_text(dir + "/quality_vs_k.dat", dat.str());
  std::ostringstream gp;
  gp << "set terminal pngcairo size 900,500\nset output 'quality_vs_k.png'\n"
     << "set xlabel 'K: output frames since the last real frame'\nset ylabel 'PSNR (dB) vs "
        "true render'\nset key top right\nset grid\nplot ";
  for (std::size_t c = 0; c < titles.size(); ++c)
    gp << (c ? ", " : "") << "'quality_vs_k.dat' using 1:" << c + 2 << " with linespoints title '"
       << titles[c] << "'";
  gp << '\n';
  write_text(dir + "/quality_vs_k.gp", gp.str());
  return run_gnuplot(dir, "quality_vs_k.gp");
}

}  // namespace terrasprite::report
