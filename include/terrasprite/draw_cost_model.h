// SPDX-License-Identifier: MIT
// Expected draw time of a frame's objects: per representation kind a
// per-instance, a per-triangle and a per-pixel term, plus a fixed per-frame
// term (the terrain). Calibrated from measured draws, refit online from
// measured frame times.
#pragma once
#include <array>
#include <span>

#include "terrasprite/object_renderer.h"

namespace terrasprite {

/// One instance: per_instance + per_triangle * triangles + per_pixel * pixels;
/// one instanced draw call of the kind adds per_draw.
struct DrawCostTerms {
  double per_draw_ms = 0;
  double per_instance_ms = 0;
  double per_triangle_ms = 0;
  double per_pixel_ms = 0;
};

/// One measured draw: `instances` instances of one kind, their triangles and
/// covered pixels (sums), and the time it took.
struct DrawSample {
  double draws = 0;  ///< draw calls (calibration: one per sample)
  double instances = 0;
  double triangles = 0;
  double pixels = 0;
  double ms = 0;
};

/// What a frame draws, per kind (sums over its instances).
struct FrameLoad {
  std::array<DrawSample, 3> kinds{};  ///< indexed by ObjectKind; `ms` unused
};

struct CostModelOptions {
  /// Online refit: recursive least squares with this forgetting factor per
  /// observed frame (1 = never forget).
  double forgetting = 0.95;
  /// Prior standard deviation of each term as a fraction of its calibrated
  /// value: how far the evidence may move it.
  double prior_fraction = 0.5;
  /// Measurement noise of one frame time, as a fraction of the frame: how
  /// much one frame is trusted.
  double noise_fraction = 0.15;
};

class DrawCostModel {
 public:
  explicit DrawCostModel(const CostModelOptions& options = {});

  /// Least-squares fit of one kind's terms to measured draws (terms that come
  /// out negative are dropped and the rest refit). Fewer than one sample
  /// leaves the terms as they were. Draws of one instance each cannot tell a
  /// draw call from an instance: the fitted constant is split
  /// `draw_share` to the draw call, the rest to the instance (the online
  /// refit moves both).
  void calibrate(ObjectKind kind, std::span<const DrawSample> samples, double draw_share);
  void set_terms(ObjectKind kind, const DrawCostTerms& terms);
  void set_frame_ms(double ms) {
    frame_ms_ = ms;
    prior_set_ = false;
  }
  const DrawCostTerms& terms(ObjectKind kind) const { return terms_[std::size_t(kind)]; }
  double frame_ms() const { return frame_ms_; }

  /// Expected time of one instance drawn as `kind` (its draw call's share not included).
  double instance_ms(ObjectKind kind, double triangles, double pixels) const;
  /// Expected time of a frame: the fixed term plus every kind's load.
  double predict(const FrameLoad& load) const;

  /// Moves every term towards explaining `measured_ms` for `load`: recursive
  /// least squares on a multiplier per term (prior 1 +- prior_fraction, each
  /// clamped to [0.05, 20]) over the ten terms' calibrated contributions.
  void observe(const FrameLoad& load, double measured_ms);

 private:
  static constexpr int kTerms = 13;
  void reset_prior();
  std::array<double, kTerms> theta() const;
  std::array<double, kTerms> calibrated_{};
  std::array<double, kTerms> multipliers_{};
  CostModelOptions options_;
  std::array<DrawCostTerms, 3> terms_{};
  double frame_ms_ = 0;
  std::array<double, kTerms * kTerms> covariance_{};
  double prior_trace_ = 0;
  bool prior_set_ = false;
};

}  // namespace terrasprite
