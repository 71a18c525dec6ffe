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
#include "terrasprite/common/stats.h"
#include "terrasprite/hybrid/depth_occlusion.h"
#include "terrasprite/hybrid/expected_quality.h"
#include "terrasprite/hybrid/frame_pace.h"
#include "terrasprite/hybrid/instance_view.h"
#include "terrasprite/hybrid/measured_fixed_time.h"

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

/// The chosen instances by (model, representation): one instanced draw each.
using DrawGroups = std::map<GroupKey, std::pair<Representation, std::vector<ObjectInstance>>>;

/// The machine's pace as the depth read-back showed it (neutral without one).
struct ReadBackPace {
  FrameLoad load;        ///< known_extra_ms: the terrain's deviation from usual
  double factor = 1;     ///< on the prediction of what follows the read-back
  double log_ratio = 0;  ///< log(read-back / usual)
};

/// The frame's expected SSIM from the tables' values, before any penalty.
double expected_ssim(const std::vector<InstanceOptions>& frame, const FrameSelection& sel) {
  double wsum = 0, expected = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const RepresentationOption& chosen = frame[i].options[std::size_t(sel.option[i])];
    wsum += frame[i].weight;
    expected += frame[i].weight * (chosen.ssim + chosen.penalty);
  }
  return wsum > 0 ? expected / wsum : 1.0;
}

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
  /// per-instance knapsack cannot see. Taken off the next frame's budget.
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

  // The stages of a frame, in draw()'s order.
  bool viewport_is_image() const;
  std::vector<Viewed> view_unoccluded(const Camera& camera, const HybridScenario& scenario,
                                      bool cull, HybridFrameStats& st);
  std::vector<InstanceOptions> frame_options(std::vector<Viewed>& viewed,
                                             HybridFrameStats& st) const;
  void share_draw_calls(const std::vector<Viewed>& viewed, std::vector<InstanceOptions>& frame,
                        HybridFrameStats& st) const;
  double frame_budget(HybridScenario::Control control, PolicyOptions& po) const;
  ReadBackPace read_back_pace(bool cull, double occlusion_ms);
  double floored_budget(double computed);
  DrawGroups group_chosen(const Camera& camera, const std::vector<Viewed>& viewed,
                          const std::vector<InstanceOptions>& frame, const FrameSelection& sel,
                          HybridFrameStats& st);
  void predict_frame(double selected_ms, const ReadBackPace& paced, bool cull,
                     HybridFrameStats& st);
  void draw_groups(const DrawGroups& groups, const Camera& camera);

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
        // near the camera it is far worse than they say.
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

bool HybridObjects::Impl::viewport_is_image() const {
  // Only into an image of the options' size: elsewhere the pixel mapping
  // would be wrong, and a wrong mapping could hide what shows.
  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_VIEWPORT, viewport);
  return viewport[0] == 0 && viewport[1] == 0 && viewport[2] == options.width &&
         viewport[3] == options.height;
}

std::vector<Viewed> HybridObjects::Impl::view_unoccluded(const Camera& camera,
                                                         const HybridScenario& scenario, bool cull,
                                                         HybridFrameStats& st) {
  // Every instance in the frustum, viewed and priced, on another thread
  // while the read-back waits for the terrain's rasterisation (with a
  // software rasteriser on the drawing thread the other core is idle then).
  // Nothing here needs the depth; the occlusion test filters after.
  std::vector<Viewed> viewed;
  auto view = [&] {
    const auto v0 = std::chrono::steady_clock::now();
    viewed = view_and_price(camera, scenario);
    st.view_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - v0).count();
  };
  DepthOcclusion occluder;
  tbb::task_group views;
  if (cull) {
    views.run(view);
    const auto r0 = std::chrono::steady_clock::now();
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    occluder = DepthOcclusion(
        gl::read_depth_raw(GLuint(fbo), options.width, options.height, depth_scratch),
        options.width, options.height, camera);
    st.occlusion_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - r0).count();
  } else {
    view();
  }
  views.wait();
  std::erase_if(viewed, [&](const Viewed& c) {
    const bool hidden =
        cull && occluder.hidden(sphere_on_screen(camera, options.width, options.height,
                                                 c.view.centre_m, c.view.radius_m));
    st.occluded += hidden;
    return hidden;
  });
  return viewed;
}

std::vector<InstanceOptions> HybridObjects::Impl::frame_options(std::vector<Viewed>& viewed,
                                                                HybridFrameStats& st) const {
  std::vector<InstanceOptions> frame;
  frame.reserve(viewed.size());
  for (Viewed& c : viewed) {
    long long lo = c.options.options.front().triangles;
    for (const auto& opt : c.options.options) lo = std::min(lo, opt.triangles);
    st.triangles_min += lo;
    st.triangles_max += set.model(c.model).model().triangles();
    frame.push_back(std::move(c.options));
  }
  return frame;
}

void HybridObjects::Impl::share_draw_calls(const std::vector<Viewed>& viewed,
                                           std::vector<InstanceOptions>& frame,
                                           HybridFrameStats& st) const {
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
        if (is_drawn(opt.rep)) opt.cost_ms += cost.terms(opt.rep.kind).per_draw_ms / visible;
        cheapest = std::min(cheapest, opt.cost_ms);
      }
      st.floor_ms += cheapest;
    }
    first = end;
  }
}

double HybridObjects::Impl::frame_budget(HybridScenario::Control control, PolicyOptions& po) const {
  switch (control) {
    case HybridScenario::Control::kNone:
      return INFINITY;
    case HybridScenario::Control::kQualityStep:
      // The paper's quality step for the impostors; the meshes' budget is
      // the target as the same measured-time loop corrects it (a fixed
      // budget in predicted milliseconds would miss by the model's error).
      po.target_ssim = quality_step.quality();
      return controller.budget_ms();
    case HybridScenario::Control::kBudgetPi:
      return controller.budget_ms();
    case HybridScenario::Control::kFixed:
      return options.target_ms;
  }
  return INFINITY;
}

ReadBackPace HybridObjects::Impl::read_back_pace(bool cull, double occlusion_ms) {
  // What the terrain took in this frame is known by now (the read-back
  // waited for it): the objects get what it left (its usual time is in the
  // model's frame term; its deviation is added). What follows the
  // read-back (the objects, their draw calls) runs at the pace the
  // read-back showed: its prediction is scaled by the pace's factor (1
  // without culling).
  ReadBackPace p;
  if (cull) {
    p.load.known_extra_ms = fixed_time.deviation(occlusion_ms);
    p.log_ratio = fixed_time.last_log_ratio();
    p.factor = pace.factor(p.log_ratio);
  }
  return p;
}

double HybridObjects::Impl::floored_budget(double computed) {
  // Floored by the recent budgets (HybridOptions::objects_budget_floor): one
  // slow frame must not send every instance to its coarsest.
  if (!std::isfinite(computed)) return computed;
  double floored = computed;
  if (!recent_budgets.empty())
    floored = std::max(computed, options.objects_budget_floor *
                                     median({recent_budgets.begin(), recent_budgets.end()}));
  recent_budgets.push_back(computed);
  while (int(recent_budgets.size()) > std::max(1, options.objects_budget_window))
    recent_budgets.pop_front();
  return floored;
}

DrawGroups HybridObjects::Impl::group_chosen(const Camera& camera,
                                             const std::vector<Viewed>& viewed,
                                             const std::vector<InstanceOptions>& frame,
                                             const FrameSelection& sel, HybridFrameStats& st) {
  // Group by (model, representation); one instanced draw per group.
  DrawGroups groups;
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
    g.second.push_back(set.instances(m)[i]);
    cost.add(load, r, double(opt.triangles), viewed[k].view.pixels, int(m),
             set.model(m).culls_back_faces(r, g.second.back(), camera), viewed[k].view.on_screen);
    st.triangles += opt.triangles;
    st.instances_by_kind[std::size_t(r.kind)] += 1;
  }
  for (const auto& [key, g] : groups) {
    load.kinds[std::size_t(std::get<1>(key))].draws += 1;
    st.draws_by_kind[std::size_t(std::get<1>(key))] += 1;
  }
  return groups;
}

void HybridObjects::Impl::predict_frame(double selected_ms, const ReadBackPace& paced, bool cull,
                                        HybridFrameStats& st) {
  st.predicted_ms = cost.predict(load);
  draw_gap_ms = std::max(0.0, st.predicted_ms - cost.frame_ms(load) - selected_ms);
  st.draw_gap_ms = draw_gap_ms;
  // The pace as known time: added to the prediction, never refit.
  const double after = st.predicted_ms - cost.frame_ms(load);
  unpaced_ms = cull ? st.predicted_ms : 0.0;
  pace_x = st.predicted_ms > 0 ? paced.log_ratio * after / st.predicted_ms : 0.0;
  load.known_extra_ms += (paced.factor - 1) * after;
  st.predicted_ms = cost.predict(load);
  for (std::size_t k = 0; k < 3; ++k)
    st.predicted_by_kind_ms[k] = paced.factor * cost.kind_ms(load, ObjectKind(k));
}

void HybridObjects::Impl::draw_groups(const DrawGroups& groups, const Camera& camera) {
  // Per model, all its groups at once: one upload of their instances.
  std::vector<GlModel::Group> batch;
  for (auto it = groups.begin(); it != groups.end(); ++it) {
    if (drawn_kinds[std::size_t(std::get<1>(it->first))])
      batch.push_back({it->second.first, it->second.second});
    const auto next = std::next(it);
    if (next == groups.end() || std::get<0>(next->first) != std::get<0>(it->first)) {
      set.model(std::get<0>(it->first)).draw(batch, camera);  // nothing when empty
      batch.clear();
    }
  }
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
  HybridFrameStats st;
  // The terrain is drawn: what lies behind it needs no representation.
  const bool cull = scenario_.cull_occluded && s.viewport_is_image();
  std::vector<Viewed> viewed = s.view_unoccluded(camera, scenario_, cull, st);
  std::vector<InstanceOptions> frame = s.frame_options(viewed, st);
  s.share_draw_calls(viewed, frame, st);
  st.visible = int(frame.size());
  const auto t1 = std::chrono::steady_clock::now();

  PolicyOptions po = s.options.policy;
  const double budget = s.frame_budget(scenario_.control, po);
  st.budget_ms = budget;
  st.target_quality = po.target_ssim;
  const SelectionPolicy policy = scenario_.full ? SelectionPolicy::kStatic : scenario_.policy;
  const ReadBackPace paced = s.read_back_pace(cull, st.occlusion_ms);
  st.pace = paced.factor;
  const double objects_budget =
      s.floored_budget((budget - s.cost.frame_ms(paced.load)) / paced.factor - s.draw_gap_ms);
  st.objects_budget_ms = objects_budget;
  FrameSelection sel = select_representations(policy, frame, objects_budget, po);
  if (s.options.use_hysteresis && !scenario_.full)
    st.switches = s.hysteresis.apply(frame, sel, objects_budget);
  st.objective_greedy = sel.objective_greedy;
  st.objective_optimal = sel.objective_optimal;
  st.benefit = sel.benefit;
  st.expected_ssim = expected_ssim(frame, sel);
  const auto t2 = std::chrono::steady_clock::now();
  st.selection_ms = std::chrono::duration<double, std::milli>(t2 - t0).count() - st.occlusion_ms;
  st.policy_ms = std::chrono::duration<double, std::milli>(t2 - t1).count();

  s.load = paced.load;
  const DrawGroups groups = s.group_chosen(camera, viewed, frame, sel, st);
  s.predict_frame(sel.cost_ms, paced, cull, st);
  s.draw_groups(groups, camera);
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
