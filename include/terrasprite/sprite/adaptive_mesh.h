// SPDX-License-Identifier: MIT
// A view-dependent coarse mesh for LOD-sprite keyframes (the future work of
// Chen et al. 1999, section 5): a restricted quadtree over the height grid,
// refined where the screen-space error seen from the keyframe's camera is
// largest, under a triangle budget.
#pragma once
#include <memory>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/terrain/heightfield.h"
#include "terrasprite/sprite/error_metric.h"

namespace terrasprite {

struct AdaptiveMeshOptions {
  /// At most this many triangles (>= 2; the root alone is 2).
  long long triangle_budget = 512;
  /// A node whose screen-space error is at most this many pixels is not
  /// split (0: spend the budget on whatever errs at all).
  double tolerance_px = 0;
};

/// Node (level, i, j) of the quadtree covers samples quad_indices(width,
/// 2^level)[i..i+1] x quad_indices(height, 2^level)[j..j+1], so its children
/// nest and a uniform grid of 2^level quads is one level of it. Its
/// geometric error is the largest vertical distance (m) between a sample
/// inside it and its two triangles (diagonal NW-SE, as the uniform grid's),
/// made monotone (at least its children's). Screen-space error from a camera:
/// geometric error / distance from the eye to the node's bounding box, in
/// pixels of the view (height pixels over the field of view); nodes wholly
/// outside the view (with a margin of half its size) count an eighth.
///
/// Leaves are split largest screen-space error first. A split first splits
/// whatever keeps edge neighbours within one level (restricted quadtree), so
/// the mesh is crack-free: a leaf with a finer neighbour across an edge takes
/// that edge's midpoint and is drawn as a fan around its centre sample
/// (4 + split edges triangles); a leaf without one as two triangles. A split
/// that would take the mesh over the budget is undone and the next leaf tried.
class AdaptiveMesher {
 public:
  /// Precomputes every node's geometric error and height range (each level
  /// reads every sample once). Keeps a reference to `h` (>= 2 x 2 samples).
  explicit AdaptiveMesher(const Heightfield& h);
  ~AdaptiveMesher();
  AdaptiveMesher(const AdaptiveMesher&) = delete;
  AdaptiveMesher& operator=(const AdaptiveMesher&) = delete;

  /// The deepest level (2^levels quads per side at most; its nodes are not split).
  int levels() const;
  /// The mesh for `camera` and a width x height image, as a CoarseGrid
  /// (adaptive = true, one cell per leaf). Per cell, the metric's sample C is
  /// a full-resolution sample on one of its drawn edges (not a vertex): the
  /// centre on the NW-SE diagonal of a two-triangle leaf, else of the
  /// leaf's four quarter centres (each on a spoke from a corner to the fan's
  /// centre) the one farthest from its spoke. edge_offset, normal and
  /// max_deviation are measured against the triangles drawn. Const and
  /// thread-safe (keyframes on a second thread build their own).
  CoarseGrid build(const Camera& camera, int width, int height,
                   const AdaptiveMeshOptions& options) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> p_;
};

}  // namespace terrasprite
