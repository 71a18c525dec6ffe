// SPDX-License-Identifier: MIT
// Calibrates the draw-cost model on this machine at the sizes a walkthrough
// shows: every representation a model may be drawn as, alone, in an image of
// the bench's size, from on-screen sizes of a few dozen pixels up to larger
// than the image (an instance beside the camera). The quality tables' own
// timings (at their 50 and 200 px, in a small square image) miss the near
// field, where a relief impostor's ray-marching costs per pixel.
#pragma once
#include <string>
#include <vector>

#include "terrasprite/hybrid/draw_cost_model.h"
#include "terrasprite/objects/gl_scene_objects.h"

namespace terrasprite {

struct CostCalibrationOptions {
  int width = 1280, height = 720;  ///< the image the frames are drawn in
  int samples = 1;                 ///< its samples a pixel (MSAA), 1 to GL_MAX_SAMPLES
  double fov_y_deg = 60;           ///< the walkthrough camera's
  std::vector<int> sizes_px{48, 192, 768, 1536};  ///< bounding-sphere diameters on screen
  int repeats = 3;                                ///< median of this many timed draws
  /// An impostor's per-pixel work does not depend on the model it shows (a
  /// box ray-marched or a quad sampled): each (kind, resolution) is timed on
  /// this many models only (the first ones offering it). Meshes: every model.
  int impostor_models = 2;
  /// Meshes are timed at the smallest and the largest size only (their
  /// time is mostly triangles).
  bool mesh_two_sizes = true;
  int batch = 8;  ///< instances in the draw-call batch
  /// Meshes, at the smallest size: this many instances in a grid across the
  /// image, one draw (at most 8 for levels over 20k triangles; 0: none).
  /// Instances on one spot share the rasteriser's tiles; a walkthrough's do
  /// not, and there a level's instances cost more per triangle.
  int spread = 24;
};

/// One timed draw: model, representation, size and covered pixels, time.
struct CalibrationDraw {
  std::size_t model = 0;
  Representation rep;
  int size_px = 0;
  double triangles = 0, pixels = 0, ms = 0;  ///< of one instance
  /// Instances in the draw (on one spot): 1, or a batch at the smallest size
  /// that splits the draw call's time from the instances' (ms: the whole draw).
  int instances = 1;
  /// Draw calls: 1, or `instances` separate calls of one instance each (the
  /// batch call by call: what one more call costs inside a frame).
  int draws = 1;
  /// The `instances` were spread in a grid over the image, not on one spot
  /// (see CostCalibrationOptions::spread).
  bool spread = false;
  /// A spread batch of a mesh level whose back faces a camera above hides
  /// (GlModel::back_faces_hidden_above), timed from above its top with them
  /// culled (`culled`) and not: the pair gives the level's culled_fraction.
  /// Every other draw is timed with them drawn, as below the top.
  bool above = false, culled = false;
};

/// Draws each (model, representation) in `reps[model]` alone at each size,
/// pipeline drained, and returns the median times. Needs a current GL context;
/// impostors are built first (untimed).
std::vector<CalibrationDraw> measure_draw_costs(
    GlSceneObjects& set, const std::vector<std::vector<Representation>>& reps,
    const CostCalibrationOptions& options);

/// Fits `model` to the draws: per kind the draw call (a batch drawn call by
/// call against the same batch in one call) and a timed draw's overhead
/// (one instance against the batch: the flush, once a frame, so in no
/// term: taken off each fitted constant), meshes by kind (per-instance,
/// per-triangle, per-pixel over every model's levels: the fallback) and per
/// (model, level), impostors per kind and resolution (fixed + per-pixel over
/// the models timed), each less its draw call. A mesh level with a spread
/// batch takes its constant from it: (batch - one alone) / (n - 1), less
/// its pixels, free of the flush that a single draw's constant is fitted beside.
/// A level timed from above both ways takes its culled_fraction from the pair.
void fit_draw_costs(DrawCostModel& model, const std::vector<CalibrationDraw>& draws);

/// A table of the prediction error per kind and size: measured / predicted
/// by `model` (median over the draws of that kind and size), one line per
/// kind, for the log and the note.
std::string calibration_report(const DrawCostModel& model,
                               const std::vector<CalibrationDraw>& draws);

}  // namespace terrasprite
