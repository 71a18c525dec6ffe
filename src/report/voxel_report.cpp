// SPDX-License-Identifier: MIT
#include "terrasprite/report/voxel_report.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/report/terrain_json.h"

namespace terrasprite::report {
namespace {

nlohmann::json variant_json(const VoxelVariantResult& v) {
  nlohmann::json by_threads = nlohmann::json::object();
  for (auto [threads, ms] : v.median_ms_by_threads) by_threads[std::to_string(threads)] = ms;
  return {{"name", to_string(v.variant)},
          {"threads", v.threads},
          {"frames_timed", v.frame_ms.size()},
          {"median_ms", v.median_ms},
          {"p95_ms", v.p95_ms},
          {"ns_per_pixel", v.ns_per_pixel},
          {"speedup_vs_naive", v.speedup_vs_naive},
          {"scaling_2v1", number_or_null(v.scaling_2v1)},
          {"median_ms_by_threads", by_threads},
          {"mean_ssim", v.ssim.mean},
          {"min_ssim", v.ssim.min},
          {"mean_ssim_terrain", v.ssim_terrain.mean},
          {"mean_psnr", v.psnr.mean},
          {"mean_flip", v.flip.mean}};
}

nlohmann::json per_frame_json(const VoxelBenchResult& r) {
  nlohmann::json rows = nlohmann::json::array();
  for (const VoxelFrameRow& f : r.per_frame) {
    nlohmann::json row = {{"frame", f.frame}};
    for (std::size_t v = 0; v < kVoxelBenchVariants.size(); ++v) {
      const std::string name = to_string(kVoxelBenchVariants[v]);
      if (f.ms[v]) row[name + "_ms"] = *f.ms[v];
      if (f.ssim[v]) row[name + "_ssim"] = *f.ssim[v];
    }
    if (f.reference_ms) row["reference_ms"] = *f.reference_ms;
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

nlohmann::json voxel_bench_json(const VoxelBenchResult& r) {
  nlohmann::json variants = nlohmann::json::array();
  for (const VoxelVariantResult& v : r.variants) variants.push_back(variant_json(v));
  nlohmann::json pitch = nlohmann::json::array();
  for (const VoxelPitchRow& p : r.pitch_table)
    pitch.push_back({{"pitch_deg", p.pitch_deg},
                     {"threads", p.threads},
                     {"median_ms", p.median_ms},
                     {"fps", p.fps}});
  nlohmann::json sweep = nlohmann::json::array();
  for (const VoxelSizeRow& s : r.terrain_size_sweep)
    sweep.push_back({{"samples", s.samples},
                     {"frames", s.frames},
                     {"median_ms", s.median_ms},
                     {"p95_ms", s.p95_ms}});
  return {{"device", fmt::format("cpu, {} hardware threads", r.hardware_threads)},
          {"terrain", terrain_json(r.terrain)},
          {"size", {r.width, r.height}},
          {"path", r.path},
          {"frames", r.frames},
          {"score_every", r.score_every},
          {"scored_frames", r.scored_frames},
          {"pixel_voxel_ratio", r.pixel_voxel_ratio},
          {"reference", {{"supersample", r.supersample}, {"median_ms", r.reference_median_ms}}},
          {"threads", r.threads},
          {"default_variant", to_string(kVoxelBenchVariants.back())},
          {"variants", variants},
          {"scaling_2v1", number_or_null(r.scaling_2v1)},
          {"pitch_table", pitch},
          {"terrain_size_sweep", sweep},
          {"per_frame", per_frame_json(r)}};
}

std::string write_voxel_plot(const VoxelBenchResult& r, const std::string& dir) {
  // Every variant but naive (drawn on scored frames only).
  std::vector<const VoxelVariantResult*> shown;
  for (const VoxelVariantResult& v : r.variants)
    if (v.variant != VoxelVariant::kNaive) shown.push_back(&v);
  if (shown.empty()) return "";
  std::ostringstream dat;
  dat << "# frame";
  for (const VoxelVariantResult* v : shown) dat << ' ' << to_string(v->variant) << "_ms";
  dat << '\n';
  for (std::size_t i = 0; i < shown[0]->frame_ms.size(); ++i) {
    dat << i;
    for (const VoxelVariantResult* v : shown) dat << ' ' << v->frame_ms[i];
    dat << '\n';
  }
  write_text(dir + "/frame_times.dat", dat.str());
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1000,500\nset output 'frame_times.png'\n"
     << "set xlabel 'frame along the path'\nset ylabel 'ms per frame'\nset key top left\nset grid\n"
     << "plot ";
  for (std::size_t k = 0; k < shown.size(); ++k)
    gp << (k ? ", " : "") << "'frame_times.dat' using 1:" << k + 2 << " with lines title '"
       << to_string(shown[k]->variant) << "'";
  gp << '\n';
  write_text(dir + "/frame_times.gp", gp.str());
  return run_gnuplot(dir, "frame_times.gp");
}

}  // namespace terrasprite::report
