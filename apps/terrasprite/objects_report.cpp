// SPDX-License-Identifier: MIT
// The quality table's report: .dat files and gnuplot plots of the paper's
// Figure 1 (quality over phi x theta at three sizes), Figure 2 (quality vs
// on-screen size per resolution) and Figure 3 (draw time vs quality), and
// Table 1 (lowest resolution reaching each target) as Markdown.
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "objects_table.h"
#include "terrasprite/report/plot.h"
#include "terrasprite/common/error.h"

namespace terrasprite::cli {
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

// Figure 1: SSIM over (phi, theta) at the largest, middle and smallest size,
// at the first measured heading (the model lit from one side).
std::string figure1(const QualityTable& t, const TableOptions& o, OutputDir& out) {
  std::vector<int> sizes = o.sizes_px;
  std::sort(sizes.begin(), sizes.end());
  const std::vector<int> pick = {sizes.back(), sizes[sizes.size() / 2], sizes.front()};
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
    report::write_text(out.file(name + ".dat"), dat.str());
    gp += fmt::format(
        "set output '{0}.png'\nset multiplot layout 1,3 title 'SSIM over viewing angle: {1}'\n"
        "set xlabel 'phi (deg)'; set ylabel 'theta (deg)'; set view map; set cbrange [0.5:1]\n",
        name, rep_label(*q));
    for (int i = 0; i < 3; ++i)
      gp += fmt::format("set title '{} px'\nsplot '{}.dat' index {} u 1:2:3 w pm3d notitle\n",
                        pick[i], name, i);
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
    report::write_text(out.file(name + ".dat"), dat.str());
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
  report::write_text(out.file("fig3.dat"), dat.str());
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
      md << "\n|---|" << std::string(targets.size() * 4, '-') << "|\n";
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

void write_objects_report(const QualityTable& t, const TableOptions& o, OutputDir& out) {
  std::string gp = "set terminal pngcairo size 1500,480 font 'sans,10'\n" + figure1(t, o, out) +
                   "set terminal pngcairo size 900,600 font 'sans,10'\n" + figure2(t, o, out) +
                   figure3(t, o, out);
  report::write_text(out.file("plots.gp"), gp);
  report::write_text(out.file("table1.md"), table1_markdown(t, o));
  const std::string failed = report::run_gnuplot(out.partial().string(), "plots.gp");
  if (!failed.empty()) fmt::print(stderr, "warning: {}; .dat files kept without plots\n", failed);
}

}  // namespace terrasprite::cli
