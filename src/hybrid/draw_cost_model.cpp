// SPDX-License-Identifier: MIT
// Cost model in the spirit of Funkhouser & Sequin (SIGGRAPH 1993), section
// 4.1 (time = max of per-primitive and per-pixel work, here their sum with a
// per-instance term), fitted by least squares and refit online by recursive
// least squares with exponential forgetting.
#include "terrasprite/draw_cost_model.h"

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

std::array<double, 13> features(const FrameLoad& load) {
  std::array<double, 13> x{1.0};
  for (std::size_t k = 0; k < 3; ++k) {
    x[1 + 4 * k] = load.kinds[k].draws;
    x[2 + 4 * k] = load.kinds[k].instances;
    x[3 + 4 * k] = load.kinds[k].triangles;
    x[4 + 4 * k] = load.kinds[k].pixels;
  }
  return x;
}

}  // namespace

DrawCostModel::DrawCostModel(const CostModelOptions& options) : options_(options) {}

void DrawCostModel::set_terms(ObjectKind kind, const DrawCostTerms& terms) {
  terms_[std::size_t(kind)] = terms;
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

double DrawCostModel::instance_ms(ObjectKind kind, double triangles, double pixels) const {
  const DrawCostTerms& t = terms_[std::size_t(kind)];
  return t.per_instance_ms + t.per_triangle_ms * triangles + t.per_pixel_ms * pixels;
}

double DrawCostModel::predict(const FrameLoad& load) const {
  double ms = frame_ms_;
  for (int k = 0; k < 3; ++k) {
    const DrawSample& s = load.kinds[k];
    const DrawCostTerms& t = terms_[std::size_t(k)];
    ms += t.per_draw_ms * s.draws + t.per_instance_ms * s.instances +
          t.per_triangle_ms * s.triangles + t.per_pixel_ms * s.pixels;
  }
  return ms;
}

std::array<double, DrawCostModel::kTerms> DrawCostModel::theta() const {
  return {frame_ms_,
          terms_[0].per_draw_ms,
          terms_[0].per_instance_ms,
          terms_[0].per_triangle_ms,
          terms_[0].per_pixel_ms,
          terms_[1].per_draw_ms,
          terms_[1].per_instance_ms,
          terms_[1].per_triangle_ms,
          terms_[1].per_pixel_ms,
          terms_[2].per_draw_ms,
          terms_[2].per_instance_ms,
          terms_[2].per_triangle_ms,
          terms_[2].per_pixel_ms};
}

void DrawCostModel::reset_prior() {
  // The unknowns are multipliers on the calibrated terms (1 = as calibrated),
  // so every unknown has the same scale whatever its unit.
  calibrated_ = theta();
  multipliers_.fill(1.0);
  covariance_.fill(0);
  for (int i = 0; i < kTerms; ++i)
    covariance_[std::size_t(i * kTerms + i)] = options_.prior_fraction * options_.prior_fraction;
  prior_trace_ = kTerms * options_.prior_fraction * options_.prior_fraction;
  prior_set_ = true;
}

void DrawCostModel::observe(const FrameLoad& load, double measured_ms) {
  if (!prior_set_) reset_prior();
  const std::array<double, kTerms> x = features(load);
  std::array<double, kTerms> z{};  // each term's calibrated contribution, ms
  for (int i = 0; i < kTerms; ++i)
    z[std::size_t(i)] = calibrated_[std::size_t(i)] * x[std::size_t(i)];
  auto P = [&](int i, int j) -> double& { return covariance_[std::size_t(i * kTerms + j)]; };
  std::array<double, kTerms> pz{};
  double zpz = 0, predicted = 0;
  for (int i = 0; i < kTerms; ++i) {
    for (int j = 0; j < kTerms; ++j) pz[std::size_t(i)] += P(i, j) * z[std::size_t(j)];
    zpz += z[std::size_t(i)] * pz[std::size_t(i)];
    predicted += z[std::size_t(i)] * multipliers_[std::size_t(i)];
  }
  if (!(predicted > 0) || !(measured_ms > 0)) return;
  // Relative residual, so one frame weighs the same at 10 ms and at 1 s.
  const double noise = predicted * predicted * options_.noise_fraction * options_.noise_fraction;
  const double lambda = options_.forgetting;
  const double denom = lambda * noise + zpz;
  const double residual = measured_ms - predicted;
  for (int i = 0; i < kTerms; ++i)
    multipliers_[std::size_t(i)] = std::clamp(
        multipliers_[std::size_t(i)] + pz[std::size_t(i)] / denom * residual, 0.05, 20.0);
  double trace = 0;
  for (int i = 0; i < kTerms; ++i)
    for (int j = 0; j < kTerms; ++j) {
      P(i, j) = (P(i, j) - pz[std::size_t(i)] * pz[std::size_t(j)] / denom) / lambda;
      if (i == j) trace += P(i, i);
    }
  // Forgetting inflates directions no frame excites; never past the prior's size.
  if (trace > prior_trace_)
    for (double& v : covariance_) v *= prior_trace_ / trace;
  const auto m = [&](int i) { return calibrated_[std::size_t(i)] * multipliers_[std::size_t(i)]; };
  frame_ms_ = m(0);
  for (int k = 0; k < 3; ++k)
    terms_[std::size_t(k)] = {m(1 + 4 * k), m(2 + 4 * k), m(3 + 4 * k), m(4 + 4 * k)};
}

}  // namespace terrasprite
