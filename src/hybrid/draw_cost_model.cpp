// SPDX-License-Identifier: MIT
// Cost model in the spirit of Funkhouser & Sequin (SIGGRAPH 1993), section
// 4.1 (time = max of per-primitive and per-pixel work, here their sum with a
// per-instance term), fitted by least squares and refit online by recursive
// least squares with exponential forgetting.
#include "terrasprite/hybrid/draw_cost_model.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace terrasprite {
namespace {

/// Least squares over the columns in `use`, column-scaled; false when singular.
bool solve_subset(std::span<const DrawSample> samples, const std::array<bool, 3>& use,
                  std::array<double, 3>& out) {
  auto feature = [](const DrawSample& s, int j) {
    return j == 0 ? s.instances : j == 1 ? s.triangles : s.pixels;
  };
  std::vector<int> cols;
  for (int j = 0; j < 3; ++j)
    if (use[j]) cols.push_back(j);
  const std::size_t n = cols.size();
  std::array<double, 3> scale{1, 1, 1};
  for (std::size_t a = 0; a < n; ++a) {
    double m = 0;
    for (const DrawSample& s : samples) m = std::max(m, std::abs(feature(s, cols[a])));
    scale[a] = m > 0 ? m : 1;
  }
  double A[3][4] = {};
  for (const DrawSample& s : samples)
    for (std::size_t a = 0; a < n; ++a) {
      const double xa = feature(s, cols[a]) / scale[a];
      for (std::size_t b = 0; b < n; ++b) A[a][b] += xa * feature(s, cols[b]) / scale[b];
      A[a][n] += xa * s.ms;
    }
  for (std::size_t a = 0; a < n; ++a) {  // Gauss-Jordan with partial pivoting
    std::size_t p = a;
    for (std::size_t r = a + 1; r < n; ++r)
      if (std::abs(A[r][a]) > std::abs(A[p][a])) p = r;
    if (std::abs(A[p][a]) < 1e-12) return false;
    std::swap(A[a], A[p]);
    for (std::size_t r = 0; r < n; ++r) {
      if (r == a) continue;
      const double f = A[r][a] / A[a][a];
      for (std::size_t c = a; c <= n; ++c) A[r][c] -= f * A[a][c];
    }
  }
  out = {0, 0, 0};
  for (std::size_t a = 0; a < n; ++a) out[std::size_t(cols[a])] = A[a][n] / A[a][a] / scale[a];
  return true;
}

/// A representation's calibration key: meshes by level, impostors by kind and resolution.
std::tuple<int, int, int, int> key(const Representation& rep, int model) {
  return {model, int(rep.kind), rep.kind == ObjectKind::kMesh ? rep.level : 0,
          rep.kind == ObjectKind::kMesh ? 0 : rep.resolution};
}

}  // namespace

DrawCostModel::DrawCostModel(const CostModelOptions& options) : options_(options) {}

void DrawCostModel::set_terms(ObjectKind kind, const DrawCostTerms& terms) {
  terms_[std::size_t(kind)] = terms;
  effective_ = terms_;
  prior_set_ = false;
}

void DrawCostModel::calibrate(ObjectKind kind, std::span<const DrawSample> samples,
                              double draw_share) {
  if (samples.empty()) return;
  std::array<bool, 3> use{true, true, true};
  for (int round = 0; round < 3; ++round) {
    std::array<double, 3> t{};
    if (!solve_subset(samples, use, t)) {
      // Too few distinct samples: drop the last term still in use.
      for (int j = 2; j >= 0; --j)
        if (use[j]) {
          use[j] = false;
          break;
        }
      continue;
    }
    const auto worst = std::min_element(t.begin(), t.end());
    if (*worst >= 0) {
      set_terms(kind, {draw_share * t[0], (1 - draw_share) * t[0], t[1], t[2]});
      return;
    }
    use[std::size_t(worst - t.begin())] = false;
  }
}

void DrawCostModel::calibrate(const Representation& rep, std::span<const PixelSample> samples,
                              int model) {
  if (samples.empty()) return;
  // Least squares on (1, pixels) through the same solver: instances = 1,
  // triangles = 0 (a representation's triangles are fixed: in the constant).
  // Each row divided by its time: the relative error is minimised, so a
  // 0.1 ms draw at 48 px counts as much as a 100 ms one filling the image.
  std::vector<DrawSample> s;
  for (const PixelSample& p : samples)
    if (p.ms > 0) s.push_back({1, 1 / p.ms, 0, p.pixels / p.ms, 1.0});
  std::array<double, 3> t{};
  RepresentationCost c;
  if (solve_subset(s, {true, false, true}, t) && t[0] >= 0 && t[2] >= 0) {
    c = {t[0], t[2]};
  } else {
    // One of them negative (or a single size): the better of either alone.
    double sp = 0, spp = 0, sm = 0;
    for (const PixelSample& p : samples) {
      sp += p.pixels * p.ms;
      spp += p.pixels * p.pixels;
      sm += p.ms;
    }
    const double mean = sm / double(samples.size()), slope = spp > 0 ? sp / spp : 0.0;
    double e_const = 0, e_slope = 0;
    for (const PixelSample& p : samples) {
      e_const += (p.ms - mean) * (p.ms - mean);
      e_slope += (p.ms - slope * p.pixels) * (p.ms - slope * p.pixels);
    }
    c = e_slope < e_const ? RepresentationCost{0, std::max(0.0, slope)}
                          : RepresentationCost{std::max(0.0, mean), 0};
  }
  set_cost(rep, c, model);
}

void DrawCostModel::set_cost(const Representation& rep, const RepresentationCost& cost, int model) {
  reps_[key(rep, model)] = cost;
}

const RepresentationCost* DrawCostModel::find(const Representation& rep, int model) const {
  auto it = reps_.find(key(rep, model));
  if (it == reps_.end() && model != kAnyModel) it = reps_.find(key(rep, kAnyModel));
  return it == reps_.end() ? nullptr : &it->second;
}

bool DrawCostModel::calibrated(const Representation& rep, int model) const {
  return find(rep, model) != nullptr;
}

double DrawCostModel::instance_ms(ObjectKind kind, double triangles, double pixels) const {
  const DrawCostTerms& t = effective_[std::size_t(kind)];
  return t.per_instance_ms + t.per_triangle_ms * triangles + t.per_pixel_ms * pixels +
         impostor_extra_ms(kind);
}

double DrawCostModel::impostor_extra_ms(ObjectKind kind) const {
  if (kind == ObjectKind::kMesh) return 0;
  return m(extra_term(kind)) * options_.impostor_extra_prior_ms;
}

namespace {

/// The share of a mesh's triangles that reach setup (DrawCostModel::instance_ms).
double triangle_share(ObjectKind kind, double on_screen) {
  return kind == ObjectKind::kMesh ? std::clamp(on_screen, 0.0, 1.0) : 1.0;
}

}  // namespace

double DrawCostModel::instance_ms(const Representation& rep, double triangles, double pixels,
                                  int model, bool culled, double on_screen) const {
  const double share = triangle_share(rep.kind, on_screen);
  const RepresentationCost* c = find(rep, model);
  if (!c) return instance_ms(rep.kind, share * triangles, pixels);
  const int k = int(rep.kind);
  const double f = culled ? c->culled_fraction : 1.0;
  return f * (m(2 + 3 * k) * share * c->fixed_ms + m(3 + 3 * k) * c->per_pixel_ms * pixels) +
         impostor_extra_ms(rep.kind);
}

void DrawCostModel::add(FrameLoad& load, const Representation& rep, double triangles, double pixels,
                        int model, bool culled, double on_screen) const {
  const std::size_t k = std::size_t(rep.kind);
  const double share = triangle_share(rep.kind, on_screen);
  DrawSample& s = load.kinds[k];
  s.instances += 1;
  s.triangles += triangles;
  s.pixels += pixels;
  const RepresentationCost* c = find(rep, model);
  const DrawCostTerms& t = terms_[k];
  const double f = c && culled ? c->culled_fraction : 1.0;
  load.fixed_ms[k] +=
      c ? f * share * c->fixed_ms : t.per_instance_ms + t.per_triangle_ms * share * triangles;
  load.pixel_ms[k] += c ? f * c->per_pixel_ms * pixels : t.per_pixel_ms * pixels;
}

std::array<double, DrawCostModel::kTerms> DrawCostModel::contributions(
    const FrameLoad& load) const {
  std::array<double, kTerms> z{frame_ms_};
  for (std::size_t k = 0; k < 3; ++k) {
    const DrawSample& s = load.kinds[k];
    const DrawCostTerms& t = terms_[k];
    z[1 + 3 * k] = t.per_draw_ms * s.draws;
    const bool summed = load.fixed_ms[k] > 0 || load.pixel_ms[k] > 0;
    z[2 + 3 * k] = summed ? load.fixed_ms[k]
                          : t.per_instance_ms * s.instances + t.per_triangle_ms * s.triangles;
    z[3 + 3 * k] = summed ? load.pixel_ms[k] : t.per_pixel_ms * s.pixels;
  }
  // The extra terms' unknowns are in units of the prior's standard deviation.
  for (ObjectKind k : {ObjectKind::kRelief, ObjectKind::kOctahedral})
    z[std::size_t(extra_term(k))] =
        load.kinds[std::size_t(k)].instances * options_.impostor_extra_prior_ms;
  return z;
}

double DrawCostModel::predict(const FrameLoad& load) const {
  const std::array<double, kTerms> z = contributions(load);
  double ms = 0;
  for (int i = 0; i < kTerms; ++i) ms += m(i) * z[std::size_t(i)];
  return ms + load.known_extra_ms;
}

double DrawCostModel::kind_ms(const FrameLoad& load, ObjectKind kind) const {
  const std::array<double, kTerms> z = contributions(load);
  const int k = int(kind);
  double ms = 0;
  for (int i = 1 + 3 * k; i <= 3 + 3 * k; ++i) ms += m(i) * z[std::size_t(i)];
  if (kind != ObjectKind::kMesh) ms += m(extra_term(kind)) * z[std::size_t(extra_term(kind))];
  return ms;
}

void DrawCostModel::reset_prior() {
  // The unknowns are multipliers on the calibrated contributions (1 = as
  // calibrated), so every unknown has the same scale whatever its unit.
  // The extra impostor terms start at 0 with a standard deviation of one
  // unit (their contribution is counted in units of that prior).
  covariance_.fill(0);
  prior_trace_ = 0;
  for (int i = 0; i < kTerms; ++i) {
    multipliers_[std::size_t(i)] = prior_mean(i);
    const double sd = is_extra(i) ? 1.0 : options_.prior_fraction;
    covariance_[std::size_t(i * kTerms + i)] = sd * sd;
    prior_trace_ += sd * sd;
  }
  prior_set_ = true;
}

void DrawCostModel::observe(const FrameLoad& load, double measured_ms) {
  if (!prior_set_) reset_prior();
  measured_ms -= load.known_extra_ms;                        // known, not the terms' to explain
  const std::array<double, kTerms> z = contributions(load);  // each term's calibrated ms
  auto P = [&](int i, int j) -> double& { return covariance_[std::size_t(i * kTerms + j)]; };
  // Only the terms in this frame's time learn from it. A term with nothing
  // in the frame (an impostor kind not drawn) would move all the same
  // through its covariance with the others, and could price its kind out
  // so that it is never drawn to correct it. Its covariance with the terms
  // that learn is dropped, its own kept unchanged (no forgetting of what no
  // frame shows; docs/results/2026-12-03-hybrid-cost-refit.md).
  std::array<bool, kTerms> in{};
  for (int i = 0; i < kTerms; ++i) in[std::size_t(i)] = z[std::size_t(i)] != 0;
  std::array<double, kTerms> pz{};
  double zpz = 0, predicted = 0;
  for (int i = 0; i < kTerms; ++i) {
    if (in[std::size_t(i)])
      for (int j = 0; j < kTerms; ++j)
        if (in[std::size_t(j)]) pz[std::size_t(i)] += P(i, j) * z[std::size_t(j)];
    zpz += z[std::size_t(i)] * pz[std::size_t(i)];
    predicted += z[std::size_t(i)] * multipliers_[std::size_t(i)];
  }
  if (!(predicted > 0) || !(measured_ms > 0)) return;
  // The frame term and the kinds' terms rise and fall together in a closed
  // loop, so a few noisy frames can trade one for another without changing
  // the frame's prediction (and drive one multiplier to its floor). Their
  // spread about the frame's mean multiplier is drawn in first (this
  // frame's prediction is unchanged); a pace every term shares is kept whole.
  if (options_.spread_retention < 1) {
    double calibrated = 0, refit = 0;  // a term not in the frame has z = 0
    for (int i = 0; i < kTerms; ++i)
      if (!is_extra(i)) {
        calibrated += z[std::size_t(i)];
        refit += z[std::size_t(i)] * multipliers_[std::size_t(i)];
      }
    if (calibrated > 0) {
      const double mean = refit / calibrated;
      for (int i = 0; i < kTerms; ++i)
        if (in[std::size_t(i)] && !is_extra(i))
          multipliers_[std::size_t(i)] =
              mean + options_.spread_retention * (multipliers_[std::size_t(i)] - mean);
    }
  }
  // Relative residual, so one frame weighs the same at 10 ms and at 1 s.
  const double noise = predicted * predicted * options_.noise_fraction * options_.noise_fraction;
  const double lambda = options_.forgetting;
  const double denom = lambda * noise + zpz;
  const double residual = measured_ms - predicted;
  for (int i = 0; i < kTerms; ++i)
    multipliers_[std::size_t(i)] =
        std::clamp(multipliers_[std::size_t(i)] + pz[std::size_t(i)] / denom * residual,
                   is_extra(i) ? 0.0 : 0.05, 20.0);
  double trace = 0;
  for (int i = 0; i < kTerms; ++i)
    for (int j = 0; j < kTerms; ++j) {
      const bool a = in[std::size_t(i)], b = in[std::size_t(j)];
      if (a && b)
        P(i, j) = (P(i, j) - pz[std::size_t(i)] * pz[std::size_t(j)] / denom) / lambda;
      else if (a || b)
        P(i, j) = 0;
      if (i == j) trace += P(i, i);
    }
  // Forgetting inflates directions no frame excites; never past the prior's size.
  if (trace > prior_trace_)
    for (double& v : covariance_) v *= prior_trace_ / trace;
  for (std::size_t k = 0; k < 3; ++k) {
    const DrawCostTerms& t = terms_[k];
    const double draw = m(int(1 + 3 * k)), fixed = m(int(2 + 3 * k)), pixel = m(int(3 + 3 * k));
    effective_[k] = {t.per_draw_ms * draw, t.per_instance_ms * fixed, t.per_triangle_ms * fixed,
                     t.per_pixel_ms * pixel};
  }
}

}  // namespace terrasprite
