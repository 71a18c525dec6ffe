// SPDX-License-Identifier: MIT
// What a loader hands to finish_model: triangles in file units and axes, one
// material per triangle. finish_model validates, computes missing normals,
// groups triangles by material and brings the model to world conventions.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "terrasprite/objects/model.h"

namespace terrasprite::objects {

struct RawModel {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  ///< empty, or one per vertex
  std::vector<glm::vec2> uvs;      ///< empty, or one per vertex
  std::vector<std::uint32_t> indices;
  std::vector<int> triangle_material;  ///< one per triangle
  std::vector<Material> materials;
  std::vector<Image> textures;
  std::vector<std::string> texture_names;
  /// The file says per material which faces are drawn (glTF's doubleSided).
  bool orientation_from_file = false;
};

Model finish_model(RawModel raw, const std::string& path, const ModelOptions& options);

/// Moves each pair of a double-sided material's triangles on the same three
/// positions, wound opposite ways, to a single-sided copy of the material
/// (appended to `raw.materials`, one per material with pairs): each side
/// then shows its own triangle, as modelled, and the other is culled at
/// set-up instead of rasterised. Degenerate triangles are left alone.
/// Returns the triangles moved.
std::size_t draw_opposite_twins_single_sided(RawModel& raw);

/// Bounds on what one model may hold (a glTF can instance a mesh many times).
inline constexpr std::size_t kMaxModelVertices = std::size_t(1) << 25;
inline constexpr std::size_t kMaxModelTriangles = std::size_t(1) << 25;

/// A loader library's error or warning text as one short line: line ends
/// become "; ", trailing full stops go, a word (a data URI) longer than 48
/// characters is cut with "...", and so is the line past `max` characters.
std::string one_line(std::string_view text, std::size_t max = 200);

/// `bytes` is the whole file at `path`; `path` names it in messages and
/// locates the files it refers to (materials, textures, buffers).
Model load_obj(const std::string& path, const std::string& bytes, const ModelOptions& options);
Model load_gltf(const std::string& path, const std::string& bytes, const ModelOptions& options);

}  // namespace terrasprite::objects
