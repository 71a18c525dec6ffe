// SPDX-License-Identifier: MIT
// The polygonal level-of-detail chain of a model (the progressive-mesh
// representation of Jehaes, Lamotte, Tack 2008), built with meshoptimizer.
#pragma once
#include <vector>

#include "terrasprite/objects/model.h"

namespace terrasprite {

/// One level: its own vertex streams (normals recomputed for the simplified
/// surface, vertex cache and fetch optimised) and its parts, whose materials
/// index the source Model's materials.
struct LodLevel {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;
  std::vector<MeshPart> parts;
  /// Geometric deviation from the full model, metres: meshoptimizer's error
  /// of each simplification step (converted with meshopt_simplifyScale),
  /// summed down the chain; for levels of at most 4096 triangles at least the
  /// measured largest distance from ~1000 full-model vertices (the extremes
  /// along each axis among them) to the level's surface. 0 for level 0;
  /// never smaller than the level before.
  double error_m = 0.0;
  bool sloppy = false;  ///< made by meshopt_simplifySloppy (topology not kept)
  std::size_t triangles() const { return indices.size() / 3; }
  std::size_t bytes() const {
    return positions.size() * (sizeof(glm::vec3) * 2 + sizeof(glm::vec2)) + indices.size() * 4;
  }
};

struct LodOptions {
  double ratio = 0.5;          ///< triangles of each level / triangles of the one before, (0, 1)
  double min_fraction = 0.01;  ///< stop once a level has at most this fraction of the full count
  int min_triangles = 4;       ///< ... or this few triangles
  /// Normals of simplified levels: smooth, except across edges where the
  /// faces turn by more than this (models whose file carries normals only).
  double crease_deg = 45.0;
};

/// Level 0 is the full model (cache and fetch optimised); each next level has
/// at most `ratio` times the triangles of the one before (strictly fewer)
/// and an error at least as large. Levels come from meshopt_simplify with the
/// mesh's open borders locked, on the mesh welded by (position, uv, material)
/// so per-face split normals do not lock every edge; when it stalls above
/// 1.5x its target (locked borders, seams) meshopt_simplifySloppy takes over,
/// run on each colour region on its own (UV islands, merged per material where
/// their uv bounds share a centre: one swatch of a palette atlas) with the
/// target shared in proportion, so a triangle never takes a uv of another
/// swatch; a small region may vanish on a coarse level. Before a quadric
/// step, disconnected parts no larger than the level's error and under 5% of
/// the model's radius are left out (at most as many triangles as the step
/// removes), so their triangles go to the parts that shape the model.
std::vector<LodLevel> build_lod_chain(const Model& model, const LodOptions& options = {});

}  // namespace terrasprite
