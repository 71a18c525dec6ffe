// SPDX-License-Identifier: MIT
// Per frame: view each instance, list its options (expected quality from the
// tables, expected cost from the cost model), choose, steady the choice,
// draw each (model, representation) group with one instanced draw.
#include "terrasprite/hybrid/hybrid_objects.h"

#include <tbb/task_group.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <map>
#include <tuple>

#include "gl/render_target.h"
#include "terrasprite/hybrid/depth_occlusion.h"
#include "terrasprite/hybrid/expected_quality.h"
#include "terrasprite/hybrid/frame_pace.h"
#include "terrasprite/hybrid/instance_view.h"
#include "terrasprite/hybrid/measured_fixed_time.h"
#include "terrasprite/common/stats.h"

namespace terrasprite {
namespace {

struct Offer {
  Representation rep;
  QualityInterpolator quality;
  long long triangles = 0;
  double error_m = 0;
  bool shared_layout = false;  ///< measured on the model's common views: reuse its weights
};

bool offered(const HybridScenario& s, ObjectKind k) {
  return std::find(s.kinds.begin(), s.kinds.end(), k) != s.kinds.end();
}

using GroupKey = std::tuple<std::size_t, int, int, int>;  // model, kind, level, resolution

/// An instance in the view frustum, its options listed and priced.
struct Viewed {
  std::size_t model = 0, index = 0;
  InstanceView view;
  InstanceOptions options;
};

}  // namespace

struct HybridObjects::Impl {
  GlSceneObjects& set;
  DrawCostModel cost;
  DrawCostModel calibrated_cost;  ///< before any online refit (forget_feedback)
  HybridOptions options;
  std::vector<std::vector<Offer>> offers;  ///< per model
  SelectionHysteresis hysteresis;
  BudgetController controller;
  QualityStepController quality_step;
  FrameLoad load;  ///< of the last frame, for the cost model's refit
  /// The last frame's predicted time less what the policy saw (terrain plus
  /// the chosen options' costs): the draw calls of the (model,
  /// representation) groups beyond one per model and kind, which a
  /// per-instance knapsack cannot see. Taken off the next frame's budget:
  /// under a 10 ms target the frames were predicted 1.7-2.5 ms over it.
  double draw_gap_ms = 0;
  /// The terrain's time in each frame, as the read-back measured it.
  MeasuredFixedTime fixed_time;
  /// The machine's pace that read-back showed, on what follows it.
  FramePace pace;
  /// The last frame's prediction without the pace (0: nothing to fit) and
  /// its log(read-back / usual) times the share of that prediction after
  /// the read-back (the whole frame's log moves by that much).
  double unpaced_ms = 0, pace_x = 0;
  std::array<bool, 3> drawn_kinds{true, true, true};  ///< set_drawn_kinds
  /// The objects' budgets of the last frames as computed, before the floor.
  std::deque<double> recent_budgets;
  /// The occlusion test's resolve of a multisampled target, kept between frames.
  std::optional<gl::RenderTarget> depth_scratch;

  /// Every instance in `camera`'s frustum with its options, in model order.
  /// Reads only what no frame changes until the selection (tables, cost
  /// model, instances): it runs beside the occlusion read-back.
  std::vector<Viewed> view_and_price(const Camera& camera, const HybridScenario& scenario) const;

  Impl(GlSceneObjects& s, const DrawCostModel& c, const HybridOptions& o)
      : set(s),
        cost(c),
        calibrated_cost(c),
        options(o),
        hysteresis(o.hysteresis),
        controller(o.controller),
        quality_step(o.quality_step),
        pace(o.pace) {}
};

HybridObjects::HybridObjects(GlSceneObjects& set, const std::vector<QualityTable>& tables,
                             const DrawCostModel& cost, HybridScenario scenario,
                             const HybridOptions& options)
    : scenario_(std::move(scenario)) {
  HybridOptions o = options;
  o.controller.target_ms = o.target_ms;
  o.quality_step.target_ms = o.target_ms;
  o.quality_step.start_quality = o.policy.target_ssim;
  impl_ = std::make_unique<Impl>(set, cost, o);
  impl_->offers.resize(set.model_count());
  for (std::size_t m = 0; m < set.model_count(); ++m) {
    GlModel& model = set.model(m);
    const auto& chain = model.chain();
    if (m < tables.size())
      for (const RepresentationQuality& rq : tables[m].representations) {
        if (!offered(scenario_, rq.rep.kind)) continue;
        if (rq.rep.kind == ObjectKind::kMesh && rq.rep.level >= int(chain.size())) continue;
        const double err =
            rq.rep.kind == ObjectKind::kMesh ? chain[std::size_t(rq.rep.level)].error_m : 0.0;
        impl_->offers[m].push_back({rq.rep, QualityInterpolator(rq), model.triangles(rq.rep), err});
      }
    // Full geometry is always on offer to meshes (and is the reference).
    const bool has_full = std::any_of(
        impl_->offers[m].begin(), impl_->offers[m].end(),
        [](const Offer& f) { return f.rep.kind == ObjectKind::kMesh && f.rep.level == 0; });
    if ((scenario_.full || offered(scenario_, ObjectKind::kMesh)) && !has_full)
      impl_->offers[m].push_back({Representation{}, QualityInterpolator(RepresentationQuality{}),
                                  model.triangles(Representation{}), 0.0});
    for (Offer& f : impl_->offers[m])
      f.shared_layout = f.quality.same_layout(impl_->offers[m].front().quality);
  }
}

std::vector<Viewed> HybridObjects::Impl::view_and_price(const Camera& camera,
                                                        const HybridScenario& scenario) const {
  const HybridOptions& o = options;
  const double image_px = double(o.width) * o.height;
  const double px_per_m = o.height / (2 * std::tan(glm::radians(camera.fov_y_deg) / 2));
  std::vector<Viewed> out;
  int id = 0;
  for (std::size_t m = 0; m < set.model_count(); ++m) {
    const GlModel& gl_model = set.model(m);
    const Model& model = gl_model.model();
    const auto instances = set.instances(m);
    for (std::size_t i = 0; i < instances.size(); ++i, ++id) {
      const InstanceView v = view_instance(camera, o.height, instances[i],
                                           glm::dvec3(model.center()), model.bounding_radius());
      if (!v.visible || offers[m].empty()) continue;
      InstanceOptions inst{id, v.size_px, std::min(1.0, v.pixels / image_px), {}};
      // One table lookup per instance; every representation on the same views reuses it.
      const double radius = model.bounding_radius() * instances[i].scale;
      const QualityInterpolator::Weights w =
          offers[m].front().quality.weights(v.phi_deg, v.theta_deg, v.size_px, v.heading_deg);
      for (const Offer& f : offers[m]) {
        if (scenario.full && !(f.rep.kind == ObjectKind::kMesh && f.rep.level == 0)) continue;
        // Beyond the tables' sizes an impostor's quality is unknown, and
        // near the camera it is far worse than they say (checkpoint D).
        // Within two radii the camera is inside or at the impostor's box.
        if (f.rep.kind != ObjectKind::kMesh && o.max_impostor_size_px > 0 &&
            (v.size_px > o.max_impostor_size_px || v.distance_m < 2 * radius) &&
            scenario.policy != SelectionPolicy::kImpostorOnly)
          continue;
        const ExpectedQuality q =
            f.shared_layout ? f.quality.at(w)
                            : f.quality.at(v.phi_deg, v.theta_deg, v.size_px, v.heading_deg);
        const double err_px =
            f.error_m * instances[i].scale * px_per_m / std::max(v.distance_m, 1e-6);
        const bool culled = gl_model.culls_back_faces(f.rep, instances[i], camera);
        const double penalty = o.quality_spread_penalty * q.ssim_spread;
        inst.options.push_back(
            {f.rep,
             cost.instance_ms(f.rep, double(f.triangles), v.pixels, int(m), culled, v.on_screen),
             q.ssim - penalty, q.psnr, f.triangles, err_px, penalty});
      }
      if (o.cull_px > 0 && v.size_px < o.cull_px && !scenario.full &&
          scenario.policy != SelectionPolicy::kImpostorOnly)
        inst.options.push_back(not_drawn_option());
      out.push_back({m, i, v, std::move(inst)});
    }
  }
  return out;
}

HybridObjects::~HybridObjects() = default;

void HybridObjects::prepare() {
  for (std::size_t m = 0; m < impl_->offers.size(); ++m)
    for (const Offer& f : impl_->offers[m])
      if (f.rep.kind != ObjectKind::kMesh) impl_->set.model(m).prepare(f.rep);
}

long long HybridObjects::draw(const Camera& camera) {
  Impl& s = *impl_;
  const auto t0 = std::chrono::steady_clock::now();
  const HybridOptions& o = s.options;
  HybridFrameStats st;
  // The terrain is drawn: what lies behind it needs no representation.
  DepthOcclusion occluder;
  GLint viewport[4] = {0, 0, 0, 0};
  if (scenario_.cull_occluded) glGetIntegerv(GL_VIEWPORT, viewport);
  // Only into an image of the options' size: elsewhere the pixel mapping
  // would be wrong, and a wrong mapping could hide what shows.
  const bool cull = scenario_.cull_occluded && viewport[0] == 0 && viewport[1] == 0 &&
                    viewport[2] == o.width && viewport[3] == o.height;
  // Every instance in the frustum, viewed and priced, on another thread
  // while the read-back waits for the terrain's rasterisation: with
  // llvmpipe rasterising on the drawing thread (LP_NUM_THREADS=0, two
  // cores) the other core is idle then. Nothing here needs the depth; the
  // occlusion test filters after. (Flushing the terrain earlier instead, to
  // rasterise it beside the viewing, only moved the wait into the
  // selection's time, p95 2.4 ms against 1.0, when llvmpipe had threads.)
  std::vector<Viewed> viewed;
  auto view = [&] {
    const auto v0 = std::chrono::steady_clock::now();
    viewed = s.view_and_price(camera, scenario_);
    st.view_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - v0).count();
  };
  tbb::task_group views;
  if (cull) {
    views.run(view);
    const auto r0 = std::chrono::steady_clock::now();
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    occluder = DepthOcclusion(gl::read_depth_raw(GLuint(fbo), o.width, o.height, s.depth_scratch),
                              o.width, o.height, camera);
    st.occlusion_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - r0).count();
  } else {
    view();
  }
  views.wait();
  // The instances not behind the terrain; frame[k] holds viewed[k]'s options.
  std::erase_if(viewed, [&](const Viewed& c) {
    const bool hidden = cull && occluder.hidden(sphere_on_screen(camera, o.width, o.height,
                                                                 c.view.centre_m, c.view.radius_m));
    st.occluded += hidden;
    return hidden;
  });
  std::vector<InstanceOptions> frame;
  frame.reserve(viewed.size());
  for (Viewed& c : viewed) {
    long long lo = c.options.options.front().triangles;
    for (const auto& opt : c.options.options) lo = std::min(lo, opt.triangles);
    st.triangles_min += lo;
    st.triangles_max += s.set.model(c.model).model().triangles();
    frame.push_back(std::move(c.options));
  }
  // A draw call per (model, representation) the knapsack cannot see as a
  // fixed cost: each visible instance of the model carries its share of it
  // (at most one call per representation for all of them).
  for (std::size_t first = 0; first < frame.size();) {
    std::size_t end = first;
    while (end < frame.size() && viewed[end].model == viewed[first].model) ++end;
    const double visible = double(end - first);
    for (std::size_t k = first; k < end; ++k) {
      double cheapest = INFINITY;
      for (RepresentationOption& opt : frame[k].options) {
        if (is_drawn(opt.rep)) opt.cost_ms += s.cost.terms(opt.rep.kind).per_draw_ms / visible;
        cheapest = std::min(cheapest, opt.cost_ms);
      }
      st.floor_ms += cheapest;
    }
    first = end;
  }
  st.visible = int(frame.size());
  const auto t1 = std::chrono::steady_clock::now();

  // The budget the policy spends on objects: the whole frame's, less the terrain.
  double budget = INFINITY;
  PolicyOptions po = o.policy;
  switch (scenario_.control) {
    case HybridScenario::Control::kNone:
      break;
    case HybridScenario::Control::kQualityStep:
      // The paper's quality step for the impostors; the meshes' budget is
      // the target as the same measured-time loop corrects it (a fixed
      // budget in predicted milliseconds would miss by the model's error).
      po.target_ssim = s.quality_step.quality();
      budget = s.controller.budget_ms();
      break;
    case HybridScenario::Control::kBudgetPi:
      budget = s.controller.budget_ms();
      break;
    case HybridScenario::Control::kFixed:
      budget = o.target_ms;
      break;
  }
  st.budget_ms = budget;
  st.target_quality = po.target_ssim;
  const SelectionPolicy policy = scenario_.full ? SelectionPolicy::kStatic : scenario_.policy;
  // What the terrain took in this frame is known by now (the read-back
  // waited for it): the objects get what it left (its usual time is in
  // the model's frame term; its deviation is added). Adding the instances'
  // view and the last policy's time too (up to 2.5 ms a frame) narrowed
  // nothing: sd(log measured / predicted) 0.130-0.154 in 4 runs against
  // 0.128-0.159 in 3.
  // What follows the read-back (the objects, their draw calls) runs at the
  // pace the read-back showed: its prediction is scaled by the pace's
  // factor (1 without culling).
  FrameLoad load;
  double pace = 1, pace_z = 0;
  if (cull) {
    load.known_extra_ms = s.fixed_time.deviation(st.occlusion_ms);
    pace_z = s.fixed_time.last_log_ratio();
    pace = s.pace.factor(pace_z);
  }
  st.pace = pace;
  const double computed_budget = (budget - s.cost.frame_ms(load)) / pace - s.draw_gap_ms;
  // Floored by the recent budgets (HybridOptions::objects_budget_floor): one
  // slow frame must not send every instance to its coarsest.
  double objects_budget = computed_budget;
  if (std::isfinite(computed_budget)) {
    if (!s.recent_budgets.empty())
      objects_budget =
          std::max(computed_budget, o.objects_budget_floor *
                                        median({s.recent_budgets.begin(), s.recent_budgets.end()}));
    s.recent_budgets.push_back(computed_budget);
    while (int(s.recent_budgets.size()) > std::max(1, o.objects_budget_window))
      s.recent_budgets.pop_front();
  }
  st.objects_budget_ms = objects_budget;
  FrameSelection sel = select_representations(policy, frame, objects_budget, po);
  if (o.use_hysteresis && !scenario_.full)
    st.switches = s.hysteresis.apply(frame, sel, objects_budget);
  st.objective_greedy = sel.objective_greedy;
  st.objective_optimal = sel.objective_optimal;
  st.benefit = sel.benefit;
  // The frame's expected SSIM from the tables' values, before any penalty.
  double wsum = 0, expected = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const RepresentationOption& chosen = frame[i].options[std::size_t(sel.option[i])];
    wsum += frame[i].weight;
    expected += frame[i].weight * (chosen.ssim + chosen.penalty);
  }
  st.expected_ssim = wsum > 0 ? expected / wsum : 1.0;
  const auto t2 = std::chrono::steady_clock::now();
  st.selection_ms = std::chrono::duration<double, std::milli>(t2 - t0).count() - st.occlusion_ms;
  st.policy_ms = std::chrono::duration<double, std::milli>(t2 - t1).count();

  // Group by (model, representation); one instanced draw per group.
  std::map<GroupKey, std::pair<Representation, std::vector<ObjectInstance>>> groups;
  s.load = load;
  for (std::size_t k = 0; k < frame.size(); ++k) {
    const RepresentationOption& opt = frame[k].options[std::size_t(sel.option[k])];
    const std::size_t m = viewed[k].model, i = viewed[k].index;
    const Representation& r = opt.rep;
    if (!is_drawn(r)) {
      ++st.not_drawn;
      continue;
    }
    auto& g = groups[{m, int(r.kind), r.level, r.resolution}];
    g.first = r;
    g.second.push_back(s.set.instances(m)[i]);
    s.cost.add(s.load, r, double(opt.triangles), viewed[k].view.pixels, int(m),
               s.set.model(m).culls_back_faces(r, g.second.back(), camera),
               viewed[k].view.on_screen);
    st.triangles += opt.triangles;
    st.instances_by_kind[std::size_t(r.kind)] += 1;
  }
  for (const auto& [key, g] : groups) {
    s.load.kinds[std::size_t(std::get<1>(key))].draws += 1;
    st.draws_by_kind[std::size_t(std::get<1>(key))] += 1;
  }
  st.predicted_ms = s.cost.predict(s.load);
  s.draw_gap_ms = std::max(0.0, st.predicted_ms - s.cost.frame_ms(s.load) - sel.cost_ms);
  st.draw_gap_ms = s.draw_gap_ms;
  // The pace as known time: added to the prediction, never refit.
  const double after = st.predicted_ms - s.cost.frame_ms(s.load);
  s.unpaced_ms = cull ? st.predicted_ms : 0.0;
  s.pace_x = st.predicted_ms > 0 ? pace_z * after / st.predicted_ms : 0.0;
  s.load.known_extra_ms += (pace - 1) * after;
  st.predicted_ms = s.cost.predict(s.load);
  for (std::size_t k = 0; k < 3; ++k)
    st.predicted_by_kind_ms[k] = pace * s.cost.kind_ms(s.load, ObjectKind(k));
  // Per model, all its groups at once: one upload of their instances.
  std::vector<GlModel::Group> batch;
  for (auto it = groups.begin(); it != groups.end(); ++it) {
    if (s.drawn_kinds[std::size_t(std::get<1>(it->first))])
      batch.push_back({it->second.first, it->second.second});
    const auto next = std::next(it);
    if (next == groups.end() || std::get<0>(next->first) != std::get<0>(it->first)) {
      s.set.model(std::get<0>(it->first)).draw(batch, camera);  // nothing when empty
      batch.clear();
    }
  }
  last_ = st;
  return st.triangles;
}

void HybridObjects::set_drawn_kinds(const std::array<bool, 3>& kinds) {
  impl_->drawn_kinds = kinds;
}

void HybridObjects::forget_feedback() {
  Impl& s = *impl_;
  s.cost = s.calibrated_cost;
  s.hysteresis = SelectionHysteresis(s.options.hysteresis);
  s.controller = BudgetController(s.options.controller);
  s.quality_step = QualityStepController(s.options.quality_step);
  s.load = {};
  s.draw_gap_ms = 0;
  s.fixed_time.reset();
  s.pace = FramePace(s.options.pace);
  s.unpaced_ms = 0;
  s.recent_budgets.clear();
}

void HybridObjects::feedback(double measured_ms) {
  Impl& s = *impl_;
  s.controller.update(last_.predicted_ms, measured_ms);
  s.quality_step.update(measured_ms);
  // A one-off surprise (an impostor build, a stall) says nothing about the terms.
  if (s.controller.last_was_surprise()) return;
  s.cost.observe(s.load, measured_ms);
  if (s.unpaced_ms > 0 && measured_ms > 0)
    s.pace.observe(s.pace_x, std::log(measured_ms / s.unpaced_ms));
}

}  // namespace terrasprite
