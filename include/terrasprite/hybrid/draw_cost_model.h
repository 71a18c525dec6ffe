// SPDX-License-Identifier: MIT
// Expected draw time of a frame's objects: per representation kind a
// per-instance, a per-triangle and a per-pixel term, plus a fixed per-frame
// term (the terrain). Calibrated from measured draws, refit online from
// measured frame times.
#pragma once
#include <array>
#include <map>
#include <span>
#include <tuple>

#include "terrasprite/objects/object_renderer.h"

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

/// One representation's measured cost of one instance at its on-screen
/// size: fixed + per_pixel * pixels (its draw call's share not included).
/// Calibrated per representation because the per-pixel work differs by far
/// between them (a relief impostor ray-marches 16 to 48 steps per pixel
/// depending on its resolution) and near the camera pixels dominate.
struct RepresentationCost {
  double fixed_ms = 0;
  double per_pixel_ms = 0;
  /// A mesh level's time with its hidden back faces culled (the camera
  /// above it: GlModel::culls_back_faces) as a fraction of its time with
  /// them (the one above), measured from above; 1 where nothing is culled.
  double culled_fraction = 1;
};

/// One timed draw of one representation: covered pixels (the on-screen disc
/// clipped to the image) and the time of one instance.
struct PixelSample {
  double pixels = 0;
  double ms = 0;
};

/// What a frame draws, per kind (sums over its instances).
struct FrameLoad {
  std::array<DrawSample, 3> kinds{};  ///< indexed by ObjectKind; `ms` unused
  /// Per kind, the calibrated (not refit) fixed and per-pixel milliseconds of
  /// its instances, summed by DrawCostModel::add. Zero for both with
  /// instances drawn: the kind's terms apply to the sums in `kinds`.
  std::array<double, 3> fixed_ms{}, pixel_ms{};
  /// Time this frame is known to take beyond the model's prediction, ms,
  /// measured before the selection (see MeasuredFixedTime): added to
  /// predict() and frame_ms() as it is, and taken off the measured time
  /// before the refit, which never scales it. With occlusion culling the
  /// read-back waits for the terrain's rasterisation, whose time varies
  /// with the view and the machine's pace (2-12 ms a frame here); frame
  /// time less its prediction followed it (r = 0.64), and what is known
  /// before the selection need not be noise to the controller.
  double known_extra_ms = 0;
};

struct CostModelOptions {
  /// Online refit: recursive least squares with this forgetting factor per
  /// observed frame (1 = never forget).
  double forgetting = 0.98;
  /// Prior standard deviation of each term as a fraction of its calibrated
  /// value: how far the evidence may move it.
  double prior_fraction = 0.5;
  /// Measurement noise of one frame time, as a fraction of the frame: how
  /// much one frame is trusted.
  double noise_fraction = 0.25;
  /// Per observed frame, each drawn term's multiplier keeps this fraction of
  /// its distance from the frame's mean multiplier (its predicted over its
  /// calibrated time), which stays: the calibrated ratios between terms are
  /// trusted, the machine's pace is learnt whole. 1 turns it off.
  double spread_retention = 0.95;
  /// Per impostor kind, an extra cost per instance drawn, learnt from the
  /// frames only (prior 0, standard deviation `impostor_extra_prior_ms`,
  /// never negative). An impostor costs more inside a frame than calibrated
  /// alone: over 1705 walkthrough frames, frame time less its prediction
  /// grew by 0.117 ms per relief and 0.035 ms per octahedral impostor drawn,
  /// and the error followed how many were drawn from frame to frame. 0
  /// turns it off.
  double impostor_extra_prior_ms = 0.1;
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
    effective_ = terms_;
    prior_set_ = false;
  }
  /// The kind's terms as refit so far.
  const DrawCostTerms& terms(ObjectKind kind) const { return effective_[std::size_t(kind)]; }
  /// The frame's fixed time as refit, plus `load`'s known_extra_ms.
  double frame_ms(const FrameLoad& load = {}) const {
    return frame_ms_ * m(0) + load.known_extra_ms;
  }

  /// Fits `rep`'s own cost (least squares on the relative error, non-negative
  /// terms) to timed draws at several sizes: of model `model`'s `rep`, or
  /// (model = kAnyModel) of `rep` on every model not calibrated on its own.
  /// It then overrides the kind's terms for `rep`.
  static constexpr int kAnyModel = -1;
  void calibrate(const Representation& rep, std::span<const PixelSample> samples,
                 int model = kAnyModel);
  bool calibrated(const Representation& rep, int model = kAnyModel) const;
  /// `rep`'s own calibrated cost (the model's, else any model's), or null.
  const RepresentationCost* cost(const Representation& rep, int model = kAnyModel) const {
    return find(rep, model);
  }
  void set_cost(const Representation& rep, const RepresentationCost& cost, int model = kAnyModel);

  /// Expected time of one instance drawn as `kind` (its draw call's share not included).
  double instance_ms(ObjectKind kind, double triangles, double pixels) const;
  /// Expected time of one instance of `model` drawn as `rep`: its own
  /// calibration when it has one (the model's, else any model's), else its
  /// kind's terms; the online refit applies to all.
  /// `culled`: the draw culls the level's hidden back faces (its own
  /// calibration's culled_fraction applies).
  /// `on_screen`: the part of the instance inside the view, [0, 1]
  /// (InstanceView::on_screen; clamped). A mesh's per-instance time (its
  /// triangles) is scaled by it: triangles outside the viewport are dropped
  /// before llvmpipe sets them up and bins them. Fitted to 3 walkthroughs'
  /// frame times, the meshes' predicted time inside the image (by the part
  /// of their on-screen disc) weighed 0.90 and the time outside it -0.03.
  /// Impostors' time is not scaled (not measured; their pixels are clipped
  /// already).
  double instance_ms(const Representation& rep, double triangles, double pixels,
                     int model = kAnyModel, bool culled = false, double on_screen = 1) const;
  /// Adds one instance drawn as `rep` to a frame's load (arguments as instance_ms).
  void add(FrameLoad& load, const Representation& rep, double triangles, double pixels,
           int model = kAnyModel, bool culled = false, double on_screen = 1) const;
  /// Expected time of a frame: the fixed term plus every kind's load.
  double predict(const FrameLoad& load) const;
  /// Of predict(load), kind `kind`'s part: its draw calls and instances
  /// (its impostor extra included), without the frame term and known_extra_ms.
  double kind_ms(const FrameLoad& load, ObjectKind kind) const;

  /// Moves every term towards explaining `measured_ms` for `load`: recursive
  /// least squares on a multiplier (prior 1 +- prior_fraction, clamped to
  /// [0.05, 20]) per calibrated contribution: the frame's fixed term, and per
  /// kind its draw calls, its instances' fixed and their per-pixel time.
  /// Terms with no part in `load` (a kind not drawn) are left as they are.
  void observe(const FrameLoad& load, double measured_ms);
  /// The refit's extra cost of one instance of impostor kind `kind` in a
  /// frame, ms (0 for meshes; see CostModelOptions::impostor_extra_prior_ms).
  double impostor_extra_ms(ObjectKind kind) const;

 private:
  // frame; per kind: draw, fixed, pixel; per impostor kind: extra per instance
  static constexpr int kFirstExtra = 10, kTerms = 12;
  static int extra_term(ObjectKind kind) {
    return kFirstExtra + (kind == ObjectKind::kRelief ? 0 : 1);
  }
  static bool is_extra(int i) { return i >= kFirstExtra; }
  /// Multipliers start at 1 (as calibrated); the extra terms at 0 (none).
  static double prior_mean(int i) { return is_extra(i) ? 0.0 : 1.0; }
  std::array<double, kTerms> contributions(const FrameLoad& load) const;
  void reset_prior();
  double m(int i) const { return prior_set_ ? multipliers_[std::size_t(i)] : prior_mean(i); }
  std::array<double, kTerms> multipliers_{};
  CostModelOptions options_;
  std::array<DrawCostTerms, 3> terms_{};      ///< as calibrated
  std::array<DrawCostTerms, 3> effective_{};  ///< as refit (terms())
  const RepresentationCost* find(const Representation& rep, int model) const;
  /// (model or kAnyModel, kind, level, resolution) -> cost
  std::map<std::tuple<int, int, int, int>, RepresentationCost> reps_;
  double frame_ms_ = 0;
  std::array<double, kTerms * kTerms> covariance_{};
  double prior_trace_ = 0;
  bool prior_set_ = false;
};

}  // namespace terrasprite
