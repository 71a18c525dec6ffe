// SPDX-License-Identifier: MIT
// The quality table's report: .dat files and gnuplot plots of the paper's
// Figure 1 (quality over phi x theta at three sizes), Figure 2 (quality vs
// on-screen size per resolution) and Figure 3 (draw time vs quality), and
// Table 1 (lowest resolution reaching each target) as Markdown; the JSON
// of the objects commands.
#include "terrasprite/report/objects_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "terrasprite/objects/object_layout_writer.h"
#include "terrasprite/objects/quality_table_json.h"
#include "terrasprite/report/json_writer.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/terrain/image_io.h"

namespace terrasprite::report {
namespace {

std::string rep_label(const RepresentationQuality& q) {
  return q.rep.kind == ObjectKind::kMesh
             ? fmt::format("pm L{} ({} tris)", q.rep.level, q.triangles)
             : fmt::format("{} {}", object_kind_name(q.rep.kind), q.rep.resolution);
}

// The impostor whose resolution is nearest the middle of the sweep, per kind.
const RepresentationQuality* middle_of(const QualityTable& t, ObjectKind kind) {
  std::vector<const RepresentationQuality*> v;
  for (const auto& q : t.representations)
    if (q.rep.kind == kind) v.push_back(&q);
  return v.empty() ? nullptr : v[v.size() / 2];
}

// Figure 1's panels: the largest, middle and smallest sizes, each once.
std::vector<int> figure1_sizes(std::vector<int> sizes) {
  std::sort(sizes.begin(), sizes.end());
  std::vector<int> pick = {sizes.back(), sizes[sizes.size() / 2], sizes.front()};
  pick.erase(std::unique(pick.begin(), pick.end()), pick.end());
  return pick;
}

// Figure 1: SSIM over (phi, theta) at the largest, middle and smallest size,
// at the first measured heading (the model lit from one side).
std::string figure1(const QualityTable& t, const TableOptions& o, OutputDir& out) {
  const std::vector<int> pick = figure1_sizes(o.sizes_px);
  std::string gp;
  for (ObjectKind kind : {ObjectKind::kRelief, ObjectKind::kOctahedral, ObjectKind::kMesh}) {
    const RepresentationQuality* q = middle_of(t, kind);
    if (!q) continue;
    const std::string name = fmt::format("fig1_{}", object_kind_name(kind));
    std::ostringstream dat;
    for (int size : pick) {
      dat << "# size_px " << size << "\n# phi_deg theta_deg ssim\n";
      std::map<double, std::vector<const QualitySample*>> by_phi;
      for (const QualitySample& s : q->samples)
        if (s.size_px == size && s.heading_deg == o.headings_deg.front())
          by_phi[s.phi_deg].push_back(&s);
      for (auto& [phi, row] : by_phi) {
        for (const QualitySample* s : row)
          dat << fmt::format("{} {} {:.5f}\n", s->phi_deg, s->theta_deg, s->ssim);
        dat << "\n";
      }
      dat << "\n";
    }
    write_text(out.file(name + ".dat"), dat.str());
    gp += fmt::format(
        "set output '{0}.png'\nset multiplot layout 1,{2} title 'SSIM over viewing angle: {1}'\n"
        "set xlabel 'phi (deg)'; set ylabel 'theta (deg)'; set view map; set cbrange [0.5:1]\n",
        name, rep_label(*q), pick.size());
    // pm3d fills the cells between views; the points show each view even where
    // the grid is too coarse (or too ragged) for pm3d to fill any cell.
    for (std::size_t i = 0; i < pick.size(); ++i)
      gp += fmt::format(
          "set title '{} px'\nsplot '{}.dat' index {} u 1:2:3 w pm3d notitle, '' index {} u "
          "1:2:3 w p pt 5 ps 2 palette notitle\n",
          pick[i], name, i, i);
    gp += "unset multiplot\nunset view\n";
  }
  return gp;
}

// Figure 2: mean SSIM against on-screen size, one line per representation.
std::string figure2(const QualityTable& t, const TableOptions& o, OutputDir& out) {
  std::string gp;
  for (ObjectKind kind : o.kinds) {
    const std::string name = fmt::format("fig2_{}", object_kind_name(kind));
    std::ostringstream dat;
    std::string plots;
    int index = 0;
    for (const auto& q : t.representations) {
      if (q.rep.kind != kind) continue;
      dat << "# " << rep_label(q) << "\n# size_px mean_ssim mean_psnr\n";
      std::vector<int> sizes = o.sizes_px;
      std::sort(sizes.begin(), sizes.end());
      for (int s : sizes)
        dat << fmt::format("{} {:.5f} {:.3f}\n", s, q.mean("ssim", s), q.mean("psnr", s));
      dat << "\n\n";
      plots += fmt::format("{}'{}.dat' index {} u 1:2 w lp lw 1.5 t '{}'",
                           plots.empty() ? "" : ", ", name, index++, rep_label(q));
    }
    write_text(out.file(name + ".dat"), dat.str());
    gp += fmt::format(
        "set output '{}.png'\nset title 'Quality against on-screen size: {}'\nset logscale x 2\n"
        "set xlabel 'bounding-sphere diameter (px)'; set ylabel 'mean SSIM'; set key bottom "
        "right\nplot {}\nunset logscale x\n",
        name, object_kind_name(kind), plots);
  }
  return gp;
}

// Figure 3: draw time per instance against mean SSIM, per technique and size.
std::string figure3(const QualityTable& t, const TableOptions& o, OutputDir& out) {
  std::ostringstream dat;
  std::string plots;
  int index = 0;
  for (ObjectKind kind : o.kinds)
    for (int size : o.sizes_px) {
      dat << fmt::format("# {} at {} px\n# ms_per_instance mean_ssim\n", object_kind_name(kind),
                         size);
      for (const auto& q : t.representations) {
        if (q.rep.kind != kind) continue;
        for (const SizeCost& c : q.cost)
          if (c.size_px == size)
            dat << fmt::format("{:.5f} {:.5f}\n", c.ms_per_instance, q.mean("ssim", size));
      }
      dat << "\n\n";
      plots += fmt::format("{}'fig3.dat' index {} u 1:2 w lp t '{} {} px'",
                           plots.empty() ? "" : ", ", index++, object_kind_name(kind), size);
    }
  write_text(out.file("fig3.dat"), dat.str());
  return fmt::format(
      "set output 'fig3.png'\nset title 'Draw time against quality'\nset logscale x\n"
      "set xlabel 'ms per instance (llvmpipe)'; set ylabel 'mean SSIM'; set key outside "
      "right\nplot {}\nunset logscale x\n",
      plots);
}

}  // namespace

std::string table1_markdown(const QualityTable& t, const TableOptions& o) {
  std::ostringstream md;
  md << fmt::format(
      "Table 1: {} ({} triangles) -- lowest resolution (impostors) or coarsest level (pm) "
      "whose mean quality over all views reaches the target; '-' = none.\n",
      t.model, t.triangles);
  for (ObjectKind kind : o.kinds)
    for (const char* metric : {"ssim", "psnr"}) {
      const auto& targets = std::string(metric) == "ssim" ? o.ssim_targets : o.psnr_targets;
      md << fmt::format("\n| {} {} | ", object_kind_name(kind), metric);
      for (double target : targets) md << fmt::format("{} | ", target);
      md << "\n|---|";
      for (std::size_t i = 0; i < targets.size(); ++i) md << "---|";
      md << "\n";
      for (int size : o.sizes_px) {
        md << fmt::format("| {} px | ", size);
        for (double target : targets)
          for (const TableEntry& e : t.table)
            if (e.kind == kind && e.size_px == size && e.metric == metric && e.target == target)
              md << (e.choice
                         ? fmt::format("{}{} | ", kind == ObjectKind::kMesh ? "L" : "", *e.choice)
                         : std::string("- | "));
        md << "\n";
      }
    }
  return md.str();
}

std::vector<std::string> objects_report_warnings(const TableOptions& o) {
  std::vector<std::string> w;
  const double theta_max = o.full_sphere ? 180 : 90;
  const int thetas = int(theta_max / o.angle_step_deg + 1e-9) + 1;
  const int phis = int(std::ceil(360 / o.angle_step_deg - 1e-9));
  if (thetas < 3 || phis < 4)
    w.push_back(fmt::format(
        "--angle-step {}: {} x {} views (phi x theta) a size; the fig1 heat maps show the views "
        "as points, too few for a surface (30 or less gives one)",
        o.angle_step_deg, phis, thetas));
  std::vector<int> sizes = o.sizes_px;
  std::sort(sizes.begin(), sizes.end());
  if (std::unique(sizes.begin(), sizes.end()) - sizes.begin() < 2)
    w.push_back(
        fmt::format("--sizes-px {}: one size; the fig2 lines (quality against size) "
                    "are single points",
                    o.sizes_px.front()));
  return w;
}

void write_objects_report(const QualityTable& t, const TableOptions& o, OutputDir& out) {
  std::string gp = "set terminal pngcairo size 1500,480 font 'sans,10'\n" + figure1(t, o, out) +
                   "set terminal pngcairo size 900,600 font 'sans,10'\n" + figure2(t, o, out) +
                   figure3(t, o, out);
  write_text(out.file("plots.gp"), gp);
  write_text(out.file("table1.md"), table1_markdown(t, o));
  const std::string failed = run_gnuplot(out.partial().string(), "plots.gp");
  if (!failed.empty()) fmt::print(stderr, "warning: {}; .dat files kept without plots\n", failed);
}

nlohmann::json model_info_json(const Model& model) {
  nlohmann::json textures = nlohmann::json::array();
  for (std::size_t i = 0; i < model.textures.size(); ++i)
    textures.push_back({{"name", model.texture_names[i]},
                        {"size", {model.textures[i].width, model.textures[i].height}}});
  const glm::vec3 lo = model.bounds_min, hi = model.bounds_max;
  return {{"model", model.name},
          {"triangles", model.triangles()},
          {"vertices", model.vertices()},
          {"parts", model.parts.size()},
          {"materials", model.materials.size()},
          {"normals", model.normals_from_file ? "file" : "computed"},
          {"scale_to_m", model.scale_to_m},
          {"bounds_min_m", {lo.x, lo.y, lo.z}},
          {"bounds_max_m", {hi.x, hi.y, hi.z}},
          {"bounding_radius_m", model.bounding_radius()},
          {"textures", textures}};
}

nlohmann::json cache_stats_json(const RepresentationCacheStats& s) {
  return {{"hits", s.hits},
          {"misses", s.misses},
          {"rejected", s.rejected},
          {"read_ms", s.read_ms},
          {"build_ms", s.build_ms}};
}

nlohmann::json objects_table_json(const ObjectsTableResult& r, const TableOptions& o) {
  nlohmann::json j = table_json(r.table, o);
  j["cached"] = r.cached;
  j["representation_cache"] = cache_stats_json(r.representation_cache);
  return j;
}

void write_objects_table(const ObjectsTableResult& r, const TableOptions& o, OutputDir& out,
                         const std::string& json_path, const OutputPolicy& policy) {
  const nlohmann::json j = objects_table_json(r, o);
  write_objects_report(r.table, o, out);
  write_json(j, out.file("table.json"), policy);
  if (!json_path.empty()) write_json(j, json_path, policy);
}

// The camera as a path-file keyframe (docs/formats.md), to fly or aim from.
nlohmann::json scene_camera_json(const Camera& c) {
  return {{"t", 0},
          {"position", {c.position.x, c.position.y, c.position.z}},
          {"yaw_deg", c.yaw_deg},
          {"pitch_deg", c.pitch_deg},
          {"fov_deg", c.fov_y_deg}};
}

nlohmann::json full_geometry_json(const FullGeometryResult& r) {
  nlohmann::json models = nlohmann::json::array();
  for (const FullGeometryModel& m : r.models)
    models.push_back({{"name", m.name},
                      {"file", m.file},
                      {"triangles", m.triangles},
                      {"instances", m.instances},
                      {"lod_levels", m.lod_levels}});
  return {{"gl_renderer", r.gl_renderer},
          {"size", {r.width, r.height}},
          {"instances", r.instances},
          {"load_ms", r.load_ms},
          {"representation_cache", cache_stats_json(r.representation_cache)},
          {"full_triangles", r.full_triangles},
          {"terrain_triangles", r.terrain_triangles},
          {"frame_triangles", r.frame_triangles},
          {"frames", r.frames},
          {"median_ms", r.median_ms},
          {"terrain_median_ms", r.terrain_median_ms},
          {"models", models},
          {"camera", scene_camera_json(r.camera)},
          {"placed_instances_file", "placed.json"}};
}

void write_full_geometry(const FullGeometryResult& r, OutputDir& out, const std::string& json_path,
                         const OutputPolicy& policy) {
  save_png(r.frame, out.file("frame.png"));
  write_text(out.file("placed.json"), object_layout_json(r.placed));
  const nlohmann::json j = full_geometry_json(r);
  write_json(j, out.file("scene.json"), policy);
  if (!json_path.empty()) write_json(j, json_path, policy);
}

}  // namespace terrasprite::report
