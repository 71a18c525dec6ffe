// SPDX-License-Identifier: MIT
#include "terrasprite/hybrid/cost_calibration.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <tuple>

#include "gl/render_target.h"
#include "terrasprite/common/stats.h"

namespace terrasprite {
namespace {

using Clock = std::chrono::steady_clock;

/// A camera looking at the model's centre, `elevation_deg` above level
/// (15: theta 75 deg), from where its bounding sphere spans `size_px` of the
/// image height.
Camera calibration_camera(const Model& m, const CostCalibrationOptions& o, int size_px,
                          double elevation_deg = 15) {
  const double r = m.bounding_radius();
  const double ty = std::tan(glm::radians(o.fov_y_deg) / 2);
  const double k = double(size_px) / o.height * ty;  // r / sqrt(d^2 - r^2)
  const double dist = r * std::sqrt(1.0 + 1.0 / (k * k));
  const double phi = glm::radians(30.0), elev = glm::radians(elevation_deg);
  const glm::dvec3 c(m.center());
  const glm::dvec3 eye = c + dist * glm::dvec3(-std::sin(phi) * std::cos(elev),
                                               -std::cos(phi) * std::cos(elev), std::sin(elev));
  Camera cam = Camera::look_at(eye, c, o.fov_y_deg, double(o.width) / o.height, 30.0);
  cam.near_m = dist * 0.02;
  cam.far_m = dist + 2 * r;
  return cam;
}

/// The on-screen disc of a centred sphere `size_px` across, clipped to the image.
double centred_pixels(int size_px, int width, int height) {
  return M_PI / 4 * std::min(size_px, width) * std::min(size_px, height);
}

/// Median time of one draw of `instances`, pipeline drained.
double time_instances(gl::RenderTarget& target, GlModel& model, const Representation& rep,
                      const Camera& cam, std::span<const ObjectInstance> instances, int repeats) {
  std::vector<double> ms;
  for (int k = 0; k < std::max(1, repeats); ++k) {
    target.bind_and_clear();
    glFinish();
    const auto t0 = Clock::now();
    model.draw(rep, instances, cam);
    glFinish();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  return summarize(ms).median;
}

/// Median time of one draw of `n` instances on one spot, pipeline drained.
double time_draw(gl::RenderTarget& target, GlModel& model, const Representation& rep,
                 const Camera& cam, int n, int repeats) {
  const std::vector<ObjectInstance> same(std::size_t(std::max(n, 1)));
  return time_instances(target, model, rep, cam, same, repeats);
}

/// Up to `n` instances of `m` in a grid in the plane through its centre
/// facing `cam`, `size_px` across each and 1.6 x that apart on screen.
std::vector<ObjectInstance> spread_instances(const Model& m, const Camera& cam,
                                             const CostCalibrationOptions& o, int size_px, int n) {
  const double gap_px = 1.6 * size_px;
  const int cols = std::max(1, int(o.width / gap_px) - 1),
            rows = std::max(1, int(o.height / gap_px) - 1);
  const double dist = glm::length(cam.position - glm::dvec3(m.center()));
  const double m_per_px = 2 * dist * std::tan(glm::radians(o.fov_y_deg) / 2) / o.height;
  std::vector<ObjectInstance> out;
  for (int j = 0; j < rows && int(out.size()) < n; ++j)
    for (int i = 0; i < cols && int(out.size()) < n; ++i) {
      ObjectInstance a;
      a.position = gap_px * m_per_px *
                   ((double(i) - (cols - 1) / 2.0) * cam.right() +
                    (double(j) - (rows - 1) / 2.0) * cam.up());
      out.push_back(a);
    }
  return out;
}

/// Median time of `n` separate draw calls of one instance each on one spot.
double time_calls(gl::RenderTarget& target, GlModel& model, const Representation& rep,
                  const Camera& cam, int n, int repeats) {
  const ObjectInstance one;
  std::vector<double> ms;
  for (int k = 0; k < std::max(1, repeats); ++k) {
    target.bind_and_clear();
    glFinish();
    const auto t0 = Clock::now();
    for (int c = 0; c < n; ++c) model.draw(rep, std::span(&one, 1), cam);
    glFinish();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  return summarize(ms).median;
}

/// Per kind: a timed draw's overhead and the in-frame draw call (medians
/// over the representations with batches; NaN call where none was timed).
struct DrawOverheads {
  std::array<double, 3> overhead{}, per_call{NAN, NAN, NAN};
};

DrawOverheads draw_overheads(const std::vector<CalibrationDraw>& draws) {
  using Key = std::tuple<std::size_t, int, int, int, int>;  // model, kind, level, res, size
  std::map<Key, double> single, batch, calls;
  std::map<Key, int> n_of;
  for (const CalibrationDraw& d : draws) {
    if (d.spread) continue;
    const Key key{d.model, int(d.rep.kind), d.rep.level, d.rep.resolution, d.size_px};
    if (d.instances == 1) single[key] = d.ms;
    if (d.instances > 1) (d.draws > 1 ? calls : batch)[key] = d.ms, n_of[key] = d.instances;
  }
  std::array<std::vector<double>, 3> overheads, per_call;
  for (const auto& [key, tn] : batch) {
    const auto one = single.find(key);
    if (one == single.end()) continue;
    const int n = n_of[key];
    const double instance = std::max(0.0, (tn - one->second) / (n - 1));
    const std::size_t k = std::size_t(std::get<1>(key));
    overheads[k].push_back(std::max(0.0, one->second - instance));
    if (const auto c = calls.find(key); c != calls.end())
      per_call[k].push_back(std::max(0.0, (c->second - tn) / (n - 1)));
  }
  DrawOverheads out;
  for (std::size_t k = 0; k < 3; ++k) {
    if (!overheads[k].empty()) out.overhead[k] = summarize(overheads[k]).median;
    if (!per_call[k].empty()) out.per_call[k] = summarize(per_call[k]).median;
  }
  return out;
}

/// For each mesh level of `timed` whose hidden back faces a camera above
/// culls: a spread batch seen from 60 degrees up, with the culling on and
/// off (the model's setting is left off).
void time_culled_from_above(gl::RenderTarget& target, GlModel& model, std::size_t m,
                            const std::vector<Representation>& timed,
                            const CostCalibrationOptions& o, int size,
                            std::vector<CalibrationDraw>& out) {
  const Camera cam = calibration_camera(model.model(), o, size, 60);
  const std::vector<ObjectInstance> grid = spread_instances(model.model(), cam, o, size, o.spread);
  for (const Representation& rep : timed) {
    if (rep.kind != ObjectKind::kMesh || !std::isfinite(model.back_faces_hidden_above(rep.level)))
      continue;
    const double tris = double(model.triangles(rep));
    const std::size_t n = std::min(grid.size(), tris > 20000 ? std::size_t(8) : grid.size());
    if (n < 2) continue;
    for (bool culled : {false, true}) {
      model.set_cull_hidden_back_faces(culled);
      out.push_back({m, rep, size, tris, centred_pixels(size, o.width, o.height),
                     time_instances(target, model, rep, cam, std::span(grid).first(n), o.repeats),
                     int(n), 1, true, true, culled});
    }
    model.set_cull_hidden_back_faces(false);
  }
}

}  // namespace

std::vector<CalibrationDraw> measure_draw_costs(
    GlSceneObjects& set, const std::vector<std::vector<Representation>>& reps,
    const CostCalibrationOptions& o) {
  std::vector<CalibrationDraw> out;
  gl::RenderTarget target(o.width, o.height, o.samples);
  std::map<std::pair<int, int>, int> impostor_models;  // (kind, resolution) -> models timed
  const int smallest = *std::min_element(o.sizes_px.begin(), o.sizes_px.end());
  const int largest = *std::max_element(o.sizes_px.begin(), o.sizes_px.end());
  for (std::size_t m = 0; m < reps.size() && m < set.model_count(); ++m) {
    GlModel& model = set.model(m);
    // Timed with every back face drawn, as a camera under the model's top
    // sees it; the culled fraction from above comes from its own pair.
    struct Restore {
      GlModel& model;
      bool on;
      ~Restore() { model.set_cull_hidden_back_faces(on); }
    } restore{model, model.culls_hidden_back_faces()};
    model.set_cull_hidden_back_faces(false);
    std::vector<Representation> timed;
    for (const Representation& rep : reps[m]) {
      if (rep.kind == ObjectKind::kMesh) {
        timed.push_back(rep);
      } else if (impostor_models[{int(rep.kind), rep.resolution}]++ < o.impostor_models) {
        model.prepare(rep);
        timed.push_back(rep);
      }
    }
    for (int size : o.sizes_px) {
      const Camera cam = calibration_camera(model.model(), o, size);
      // The spread grid depends on the model and the camera only; big levels
      // take its first 8.
      const std::vector<ObjectInstance> grid =
          size == smallest ? spread_instances(model.model(), cam, o, size, o.spread)
                           : std::vector<ObjectInstance>{};
      if (size == smallest && o.batch > 1)
        for (const Representation& rep : timed) {
          const double tris = double(model.triangles(rep)),
                       px = centred_pixels(size, o.width, o.height);
          out.push_back({m, rep, size, tris, px,
                         time_draw(target, model, rep, cam, o.batch, o.repeats), o.batch});
          out.push_back({m, rep, size, tris, px,
                         time_calls(target, model, rep, cam, o.batch, o.repeats), o.batch,
                         o.batch});
          const std::size_t n = std::min(grid.size(), tris > 20000 ? std::size_t(8) : grid.size());
          if (rep.kind != ObjectKind::kMesh || n < 2) continue;
          out.push_back(
              {m, rep, size, tris, px,
               time_instances(target, model, rep, cam, std::span(grid).first(n), o.repeats), int(n),
               1, true});
        }
      if (size == smallest && o.spread > 1)
        time_culled_from_above(target, model, m, timed, o, size, out);
      for (const Representation& rep : timed) {
        if (rep.kind == ObjectKind::kMesh && o.mesh_two_sizes && size != smallest &&
            size != largest)
          continue;
        out.push_back({m, rep, size, double(model.triangles(rep)),
                       centred_pixels(size, o.width, o.height),
                       time_draw(target, model, rep, cam, 1, o.repeats)});
      }
    }
  }
  return out;
}

void fit_draw_costs(DrawCostModel& model, const std::vector<CalibrationDraw>& draws) {
  // Meshes: the kind's terms over every model's levels (the fallback), and
  // each (model, level) on its own: models differ in parts (draw calls) and
  // in how their triangles fill pixels, more than one linear fit follows.
  // Impostors: each (kind, resolution) over the models timed.
  // A timed draw of one instance on its own: t1 = overhead + instance, the
  // overhead being the call and the flush at glFinish; a batch of n
  // instances in one call: tn = overhead + n instance; the same n as n
  // calls: tc = overhead + (n - 1) call + n instance. The call is what one
  // more costs inside a frame, (tc - tn) / (n - 1). The overhead (mostly
  // the flush) is paid once a frame and is in the terrain's measured time;
  // it comes off the fitted constants (charged per call, it would add draws
  // that are not there to every group of a frame;
  // docs/results/2026-12-02-hybrid-cost-calibration.md).
  const DrawOverheads oh = draw_overheads(draws);
  const std::array<double, 3>& overhead = oh.overhead;
  for (std::size_t k = 0; k < 3; ++k)
    if (std::isfinite(oh.per_call[k])) {
      DrawCostTerms t = model.terms(ObjectKind(k));
      t.per_draw_ms = oh.per_call[k];
      model.set_terms(ObjectKind(k), t);
    }
  std::vector<DrawSample> mesh;
  std::map<std::tuple<int, int, int, int>, std::vector<PixelSample>>
      own;  // model, kind, level, res
  std::map<std::tuple<int, int, int, int>, Representation> rep_of;
  for (const CalibrationDraw& d : draws) {
    if (d.instances != 1) continue;
    // Fitted with the draw call in (a small instance's time is mostly the
    // call: taken off first, what is left is noise); taken off the constant after.
    const double ms = d.ms;
    const bool mesh_rep = d.rep.kind == ObjectKind::kMesh;
    // Relative least squares (each row over its time), as for the representations.
    if (mesh_rep && ms > 0) mesh.push_back({0, 1 / ms, d.triangles / ms, d.pixels / ms, 1.0});
    const std::tuple<int, int, int, int> k{mesh_rep ? int(d.model) : DrawCostModel::kAnyModel,
                                           int(d.rep.kind), mesh_rep ? d.rep.level : 0,
                                           mesh_rep ? 0 : d.rep.resolution};
    own[k].push_back({d.pixels, ms});
    rep_of[k] = d.rep;
  }
  if (!mesh.empty()) {
    const double per_draw = model.terms(ObjectKind::kMesh).per_draw_ms;
    model.calibrate(ObjectKind::kMesh, mesh, 0.0);
    DrawCostTerms t = model.terms(ObjectKind::kMesh);
    t.per_draw_ms = per_draw;
    t.per_instance_ms = std::max(0.0, t.per_instance_ms - overhead[0]);
    model.set_terms(ObjectKind::kMesh, t);
  }
  for (const auto& [k, samples] : own) {
    const Representation& rep = rep_of[k];
    model.calibrate(rep, samples, std::get<0>(k));
    // Take the overhead off the fitted constant (the call is the kind's term).
    RepresentationCost c = *model.cost(rep, std::get<0>(k));
    c.fixed_ms = std::max(0.0, c.fixed_ms - overhead[std::size_t(rep.kind)]);
    model.set_cost(rep, c, std::get<0>(k));
  }
  // A mesh level's spread batch against one instance alone at the same size:
  // (tn - t1) / (n - 1) is an instance's time among others spread over the
  // image, with no flush in it. Its pixels (the level's own per-pixel
  // slope) come off; what is left is the level's constant (fitted beside a
  // flush far larger than it, single draws would leave it uncertain by a
  // large factor).
  for (const CalibrationDraw& d : draws) {
    if (!d.spread || d.above || d.rep.kind != ObjectKind::kMesh || d.instances < 2) continue;
    const auto one = std::find_if(draws.begin(), draws.end(), [&](const CalibrationDraw& s) {
      return !s.spread && s.instances == 1 && s.model == d.model && s.size_px == d.size_px &&
             s.rep.kind == d.rep.kind && s.rep.level == d.rep.level;
    });
    const RepresentationCost* own_cost = model.cost(d.rep, int(d.model));
    if (one == draws.end() || !own_cost) continue;
    RepresentationCost c = *own_cost;
    const double instance = (d.ms - one->ms) / double(d.instances - 1);
    c.fixed_ms = std::max(0.0, instance - c.per_pixel_ms * d.pixels);
    model.set_cost(d.rep, c, int(d.model));
  }
  // A level timed from above with its hidden back faces culled and not:
  // the ratio of the two batches, each less the timed draw's flush, scales
  // its fixed and per-pixel time where a frame culls them.
  for (const CalibrationDraw& d : draws) {
    if (!d.above || !d.culled) continue;
    const auto drawn = std::find_if(draws.begin(), draws.end(), [&](const CalibrationDraw& s) {
      return s.above && !s.culled && s.model == d.model && s.rep.kind == d.rep.kind &&
             s.rep.level == d.rep.level && s.instances == d.instances;
    });
    const RepresentationCost* own_cost = model.cost(d.rep, int(d.model));
    if (drawn == draws.end() || !own_cost || drawn->ms <= 0) continue;
    RepresentationCost c = *own_cost;
    const double culled = d.ms - overhead[0], full = drawn->ms - overhead[0];
    if (culled <= 0 || full <= 0) continue;
    c.culled_fraction = std::clamp(culled / full, 0.05, 1.0);
    model.set_cost(d.rep, c, int(d.model));
  }
}

std::string calibration_report(const DrawCostModel& model,
                               const std::vector<CalibrationDraw>& draws) {
  const DrawOverheads oh = draw_overheads(draws);            // a timed draw's, not a frame's
  std::map<std::pair<int, int>, std::vector<double>> ratio;  // (kind, size) -> measured/predicted
  std::vector<int> sizes;
  for (const CalibrationDraw& d : draws) {
    if (d.instances != 1) continue;
    const double predicted = model.instance_ms(d.rep, d.triangles, d.pixels, int(d.model)) +
                             model.terms(d.rep.kind).per_draw_ms +
                             oh.overhead[std::size_t(d.rep.kind)];
    if (predicted > 0) ratio[{int(d.rep.kind), d.size_px}].push_back(d.ms / predicted);
    if (std::find(sizes.begin(), sizes.end(), d.size_px) == sizes.end()) sizes.push_back(d.size_px);
  }
  std::string s = "measured / predicted draw time (median per kind and size):\n  kind      ";
  for (int px : sizes) s += fmt::format(" {:>8}", fmt::format("{}px", px));
  s += "\n";
  for (int k = 0; k < 3; ++k) {
    std::string line = fmt::format("  {:<10}", object_kind_name(ObjectKind(k)));
    bool any = false;
    for (int px : sizes) {
      const auto it = ratio.find({k, px});
      if (it == ratio.end()) {
        line += fmt::format(" {:>8}", "-");
        continue;
      }
      any = true;
      line += fmt::format(" {:>8.2f}", summarize(it->second).median);
    }
    if (any) s += line + "\n";
  }
  s += fmt::format("  a timed draw's overhead (flush; once a frame, in no term): {:.4f} ms\n",
                   oh.overhead[0]);
  std::string culled;
  for (const CalibrationDraw& d : draws)
    if (d.above && d.culled)
      if (const RepresentationCost* c = model.cost(d.rep, int(d.model)))
        culled += fmt::format(" {}:L{} {:.2f}", d.model, d.rep.level, c->culled_fraction);
  if (!culled.empty()) s += "  culled from above / drawn (model:level fraction):" + culled + "\n";
  s += "  terms (ms): kind, per draw call, per instance, per triangle x 1e6, per pixel x 1e6\n";
  for (int k = 0; k < 3; ++k) {
    const DrawCostTerms& t = model.terms(ObjectKind(k));
    s += fmt::format("  {:<10} {:8.4f} {:8.4f} {:8.3f} {:8.3f}\n", object_kind_name(ObjectKind(k)),
                     t.per_draw_ms, t.per_instance_ms, 1e6 * t.per_triangle_ms,
                     1e6 * t.per_pixel_ms);
  }
  return s;
}

}  // namespace terrasprite
