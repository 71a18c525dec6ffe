// SPDX-License-Identifier: MIT
// Quality tables: Jehaes, Lamotte, Tack, "Objective quality selection for
// hybrid LOD models" (GRAPP 2008), section 3.2 -- every representation
// against the full model over a sphere of views and a range of on-screen
// sizes, PSNR and SSIM masked to the pixels either image covers.
#include "terrasprite/objects/quality_table.h"

#include <fmt/format.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <memory>
#include <span>
#include <tuple>

#include "gl/render_target.h"
#include "terrasprite/common/elapsed.h"
#include "terrasprite/common/error.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kFovDeg = 20.0;
constexpr double kPsnrCap = 100.0;

void check(const TableOptions& o) {
  if (o.kinds.empty() || o.sizes_px.empty())
    throw InputError("objects table: no representations or no sizes to measure");
  for (int s : o.sizes_px)
    if (s < kMinTableSizePx || s > kMaxTableSizePx)
      throw InputError(
          fmt::format("--sizes-px: {} is outside {}..{}", s, kMinTableSizePx, kMaxTableSizePx));
  if (!(o.angle_step_deg >= kMinTableAngleStepDeg && o.angle_step_deg <= 180))
    throw InputError(fmt::format("--angle-step: {} is outside {}..180 degrees", o.angle_step_deg,
                                 kMinTableAngleStepDeg));
  check_headings(o.headings_deg, "table headings");
}

// Image side for an on-screen size: the sphere plus a margin for SSIM's windows.
int image_side(int size_px) {
  return size_px + std::max(16, size_px / 4);
}

}  // namespace

Camera table_camera(const Model& m, double phi_deg, double theta_deg, int size_px, int side,
                    double heading_deg) {
  const double r = m.bounding_radius();
  const double k = double(size_px) / side * std::tan(glm::radians(kFovDeg) / 2);
  const double dist = r * std::sqrt(1.0 + 1.0 / (k * k));
  const double phi = glm::radians(phi_deg), elev = glm::radians(90.0 - theta_deg);
  const double h = glm::radians(heading_deg);
  const glm::dvec3 c = heading_rotate(glm::dvec3(m.center()), h);
  const glm::dvec3 eye =
      c + dist * heading_rotate(glm::dvec3(-std::sin(phi) * std::cos(elev),
                                           -std::cos(phi) * std::cos(elev), std::sin(elev)),
                                h);
  Camera cam = Camera::look_at(eye, c, kFovDeg, 1.0, phi_deg + heading_deg);
  cam.near_m = std::max(dist - 2 * r, dist * 0.05);
  cam.far_m = dist + 2 * r;
  return cam;
}

namespace {

struct Shot {
  Image color;
  std::vector<std::uint8_t> covered;
};

// Shots of several representations from one camera, each in a target of
// its own: all drawn first, then all read back. A read-back drains
// llvmpipe's pipeline, and one after each draw kept the GL thread and the
// rasteriser threads waiting on each other; drawn together, the next
// target's vertices are processed while the last one is rasterised. (Tiles
// of one target would need a single read-back but move the viewport, and
// llvmpipe's snapping of vertices to its sub-pixel grid with it: up to 0.02
// mean SSIM on the coarsest levels at 25 px. Own targets give the pixels of
// one draw at a time exactly.)
class ShotSet {
 public:
  ShotSet(int side, std::size_t count, int samples) {
    for (std::size_t k = 0; k < count; ++k) targets_.emplace_back(side, side, samples);
  }

  /// Appends the shots of `reps` (in order, at most `count`) of the model at
  /// the origin turned to `heading_deg`, seen by `cam`, to `out`.
  void render(GlModel& model, std::span<const Representation> reps, double heading_deg,
              const Camera& cam, std::vector<Shot>& out) {
    const ObjectInstance origin{glm::dvec3(0.0), heading_deg, 1.0};
    for (std::size_t k = 0; k < reps.size(); ++k) {
      targets_[k].bind_and_clear();
      model.draw(reps[k], std::span(&origin, 1), cam);
    }
    for (std::size_t k = 0; k < reps.size(); ++k) {
      Shot shot{targets_[k].read_color(), {}};
      const std::vector<float> depth = targets_[k].read_depth(cam.near_m, cam.far_m);
      shot.covered.resize(depth.size());
      for (std::size_t i = 0; i < depth.size(); ++i)
        shot.covered[i] = std::isfinite(depth[i]) ? 1 : 0;
      out.push_back(std::move(shot));
    }
  }

 private:
  std::deque<gl::RenderTarget> targets_;
};

// Median time per instance of drawing `n` instances on one spot (pipeline drained).
double time_per_instance(gl::RenderTarget& target, GlModel& model, const Representation& rep,
                         const Camera& cam, int n) {
  const std::vector<ObjectInstance> same(std::size_t(std::max(n, 1)));
  std::vector<double> ms;
  for (int repeat = 0; repeat < 3; ++repeat) {
    target.bind_and_clear();
    glFinish();
    const auto t0 = Clock::now();
    model.draw(rep, same, cam);
    glFinish();
    ms.push_back(ms_since(t0) / double(same.size()));
  }
  return median(std::move(ms));
}

std::vector<Representation> representations(const GlModel& model, const TableOptions& o) {
  std::vector<Representation> reps;
  for (ObjectKind k : o.kinds) {
    if (k == ObjectKind::kMesh) {
      for (int l = 0; l < int(model.chain().size()); ++l) reps.push_back({k, l, 0, 0});
    } else {
      for (int r : o.resolutions)
        reps.push_back({k, 0, r, k == ObjectKind::kOctahedral ? o.views : 0});
    }
  }
  return reps;
}

std::vector<std::pair<double, double>> view_angles(const TableOptions& o) {
  std::vector<std::pair<double, double>> v;
  const double theta_max = o.full_sphere ? 180.0 : 90.0;
  for (double theta = 0; theta <= theta_max + 1e-9; theta += o.angle_step_deg) {
    // Straight above (or below) every azimuth is the same view turned: one sample.
    const bool pole = theta < 1e-9 || theta > 180.0 - 1e-9;
    for (double phi = 0; phi < (pole ? 1e-9 : 360.0 - 1e-9); phi += o.angle_step_deg)
      v.emplace_back(phi, theta);
  }
  return v;
}

}  // namespace

double RepresentationQuality::mean(const std::string& metric, int size_px) const {
  double sum = 0;
  int n = 0;
  for (const QualitySample& s : samples)
    if (s.size_px == size_px) {
      sum += metric == "ssim" ? s.ssim : std::min(s.psnr, kPsnrCap);
      ++n;
    }
  return n ? sum / n : NAN;
}

QualityTable measure_quality_table(GlModel& model, const TableOptions& o,
                                   const std::function<void(int, int)>& progress) {
  check(o);
  const auto start = Clock::now();
  const Model& m = model.model();
  QualityTable t;
  t.model = m.name;
  t.triangles = (long long)m.triangles();
  for (const Representation& rep : representations(model, o)) {
    RepresentationQuality q;
    q.rep = rep;
    const auto t0 = Clock::now();
    model.prepare(rep);
    glFinish();
    q.build_ms = rep.kind == ObjectKind::kMesh ? 0.0 : ms_since(t0);
    q.triangles = model.triangles(rep);
    q.bytes = model.bytes(rep);
    q.error_m = rep.kind == ObjectKind::kMesh ? model.chain()[rep.level].error_m : 0.0;
    t.representations.push_back(q);
  }
  // Every heading with every view direction, heading by heading.
  std::vector<std::tuple<double, double, double>> views;
  for (double heading : o.headings_deg)
    for (auto [phi, theta] : view_angles(o)) views.emplace_back(heading, phi, theta);
  const Representation full{ObjectKind::kMesh, 0};
  int done = 0;
  const int total = int(views.size() * o.sizes_px.size());
  for (RepresentationQuality& q : t.representations) q.samples.resize(std::size_t(total));
  // The GL thread renders view after view; each view's scores are computed
  // on TBB's threads while the next view renders (read-backs wait for the
  // rasteriser threads anyway). Level 0 is the reference itself: scored
  // against its own shot, as rendering it again gives the same pixels.
  std::vector<Representation> drawn{full};  // the reference first, then all but level 0
  for (const RepresentationQuality& q : t.representations)
    if (!(q.rep.kind == ObjectKind::kMesh && q.rep.level == 0)) drawn.push_back(q.rep);
  tbb::task_group scoring;
  // A throw on the GL thread must not leave a task writing into `t`.
  struct WaitOnExit {
    tbb::task_group& g;
    ~WaitOnExit() { g.wait(); }
  } wait_on_exit{scoring};
  std::size_t slot = 0;
  for (int size : o.sizes_px) {
    const int side = image_side(size);
    ShotSet shot_set(side, drawn.size(), o.samples);
    for (auto [heading, phi, theta] : views) {
      const Camera cam = table_camera(m, phi, theta, size, side, heading);
      auto shots = std::make_shared<std::vector<Shot>>();
      shot_set.render(model, drawn, heading, cam, *shots);
      scoring.wait();
      scoring.run([&t, shots, slot, phi, theta, size, heading] {
        const Shot& ref = shots->front();
        std::size_t next = 1;
        for (RepresentationQuality& q : t.representations) {
          const bool same = q.rep.kind == ObjectKind::kMesh && q.rep.level == 0;
          const Shot& s = same ? ref : (*shots)[next++];
          std::vector<std::uint8_t> mask(ref.covered.size());
          bool any = false;
          for (std::size_t i = 0; i < mask.size(); ++i) {
            mask[i] = ref.covered[i] | s.covered[i];
            any = any || mask[i];
          }
          // Neither image covers a sample (a flat model edge-on at 4 px):
          // both show only the background, and the whole images say so
          // (SSIM 1). Masked, the scores would be 0 / 0: NaN samples would
          // make the expected quality of every nearby view NaN and the cached
          // table unreadable (JSON null).
          if (!any) mask.clear();
          const double psnr = quality::psnr(ref.color.view(), s.color.view(), mask).rgb;
          const double ssim = quality::ssim(ref.color.view(), s.color.view(),
                                            {quality::SsimMode::kWang, false, false}, mask)
                                  .ssim;
          q.samples[slot] = {phi, theta, size, psnr, ssim, heading};
        }
      });
      ++slot;
      if (progress) progress(++done, total);
    }
    scoring.wait();
    gl::RenderTarget target(side, side, o.samples);
    const Camera timing_cam = table_camera(m, 30.0, 60.0, size, side, 0.0);
    for (RepresentationQuality& q : t.representations)
      q.cost.push_back(
          {size, time_per_instance(target, model, q.rep, timing_cam, o.timing_instances)});
  }
  const int middle = o.sizes_px[o.sizes_px.size() / 2];
  for (RepresentationQuality& q : t.representations)
    for (const SizeCost& c : q.cost)
      if (c.size_px == middle) q.ms_per_instance = c.ms_per_instance;
  t.table = derive_table(t.representations, o);
  t.build_ms = ms_since(start);
  return t;
}

void check_headings(const std::vector<double>& headings, const char* option) {
  if (headings.empty()) throw InputError(fmt::format("{}: no headings", option));
  for (std::size_t i = 0; i < headings.size(); ++i) {
    const double h = headings[i];
    if (!(h >= 0 && h < 360))
      throw InputError(fmt::format("{}: {} is outside [0, 360)", option, h));
    if (std::count(headings.begin(), headings.begin() + long(i), h))
      throw InputError(fmt::format("{}: {} is given twice", option, h));
  }
}

std::vector<TableEntry> derive_table(const std::vector<RepresentationQuality>& reps,
                                     const TableOptions& o) {
  std::vector<TableEntry> out;
  const std::pair<const char*, const std::vector<double>*> metrics[] = {{"ssim", &o.ssim_targets},
                                                                        {"psnr", &o.psnr_targets}};
  for (ObjectKind kind : o.kinds) {
    // Cheapest first: impostors by rising resolution, meshes from the coarsest level.
    std::vector<const RepresentationQuality*> order;
    for (const RepresentationQuality& q : reps)
      if (q.rep.kind == kind) order.push_back(&q);
    std::sort(order.begin(), order.end(), [&](auto* a, auto* b) {
      return kind == ObjectKind::kMesh ? a->rep.level > b->rep.level
                                       : a->rep.resolution < b->rep.resolution;
    });
    for (int size : o.sizes_px)
      for (const auto& [metric, targets] : metrics)
        for (double target : *targets) {
          TableEntry e{kind, size, metric, target, std::nullopt};
          for (const RepresentationQuality* q : order)
            if (q->mean(metric, size) >= target) {
              e.choice = kind == ObjectKind::kMesh ? q->rep.level : q->rep.resolution;
              break;
            }
          out.push_back(e);
        }
  }
  return out;
}

}  // namespace terrasprite
