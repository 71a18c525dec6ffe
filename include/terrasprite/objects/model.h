// SPDX-License-Identifier: MIT
// Object models placed on the terrain: triangle meshes loaded from Wavefront
// OBJ or glTF 2.0 (.gltf / .glb), brought to world conventions (metres, z up,
// standing on z = 0, centred on x = y = 0).
#pragma once
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/common/image.h"

namespace terrasprite {

/// A material: base colour (linear factor on the texture, RGBA in [0, 1]) and
/// optionally a base-colour texture (index into Model::textures, -1 = none).
/// A single-sided material's back faces (clockwise on screen) are not drawn.
struct Material {
  std::string name;
  glm::vec4 base_color{1.f};
  int texture = -1;
  bool double_sided = true;
};

/// A run of Model::indices drawn with one material.
struct MeshPart {
  std::uint32_t first_index = 0;  ///< into Model::indices
  std::uint32_t index_count = 0;  ///< a multiple of 3
  int material = 0;               ///< into Model::materials
};

/// An indexed triangle mesh in metres, z up, its base on z = 0 and its
/// bounding box centred on x = y = 0. positions, normals and uvs have one entry
/// per vertex (uvs are (0, 0) where the file has none); normals are unit length.
/// Every part's indices are in range, there is at least one triangle and one
/// material, and every material's texture index is valid.
struct Model {
  std::string name;  ///< the file it came from
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> indices;
  std::vector<MeshPart> parts;  ///< one per material used, in material order
  std::vector<Material> materials;
  std::vector<Image> textures;             ///< RGBA8, rows top to bottom
  std::vector<std::string> texture_names;  ///< file or embedded name, per texture
  bool normals_from_file = false;          ///< false: computed (area-weighted, smooth)
  double scale_to_m = 1.0;                 ///< metres per file unit that was applied
  glm::vec3 bounds_min{0.f}, bounds_max{0.f};

  std::size_t triangles() const { return indices.size() / 3; }
  std::size_t vertices() const { return positions.size(); }
  /// Radius of the bounding sphere centred on the bounding box's centre, metres.
  double bounding_radius() const { return 0.5 * glm::length(bounds_max - bounds_min); }
  glm::vec3 center() const { return 0.5f * (bounds_min + bounds_max); }
};

enum class UpAxis { kY, kZ };

/// The largest ModelOptions::height_m accepted, metres.
inline constexpr double kMaxModelHeightM = 1e4;
/// The largest extent of a loaded model along any axis, metres (after
/// height_m's scale): a model's bounds are always finite and drawable.
inline constexpr double kMaxModelExtentM = 1e6;

struct ModelOptions {
  UpAxis up = UpAxis::kY;  ///< the file's up axis (glTF is y-up by definition)
  /// Real height in metres (extent along up); 0 keeps file units as metres.
  double height_m = 0.0;
  /// Texture for a file without materials (OBJ without mtllib): an image path.
  std::string texture;
  /// Colour for a file without materials and without `texture`.
  glm::vec4 color{0.75f, 0.72f, 0.68f, 1.f};
  /// Whether back faces are drawn, for every material. Unset: glTF's own
  /// `doubleSided` per material (false by default, as the format says); an
  /// OBJ (which cannot say) is single-sided when closed_and_outward() holds
  /// for it, where no back face can show from outside, and double-sided
  /// otherwise. Set false for an open mesh whose openings never face the
  /// camera (a scan's base on the ground): back faces cost about a third of
  /// a dense mesh's draw time on llvmpipe.
  std::optional<bool> double_sided;
};

/// Loads an .obj, .gltf or .glb file by its extension. Throws InputError (one
/// line naming `path`) for a missing file or a directory, a truncated or
/// malformed file, an index out of range, a non-finite position, a missing
/// texture file, an unsupported accessor, zero triangles, a degenerate
/// (zero-height) model, one larger than kMaxModelExtentM, more work than the
/// loaders' bounds (docs/formats.md, Models), or a height_m outside
/// 0..kMaxModelHeightM. A missing OBJ material library is a warning on stderr.
Model load_model(const std::string& path, const ModelOptions& options = {});

/// Throws InputError naming `source` (a file, or a scene's model) when
/// `options` cannot describe a model: height_m not in 0..kMaxModelHeightM.
void check_model_options(const ModelOptions& options, const std::string& source);

/// Whether the triangles (vertices welded by exact position) form closed
/// surfaces, every edge shared by exactly two triangles in opposite
/// directions, enclosing a positive volume (counter-clockwise seen from
/// outside). Then no back face is visible from outside the mesh. Degenerate
/// triangles are ignored; no triangles: false.
bool closed_and_outward(const std::vector<glm::vec3>& positions,
                        const std::vector<std::uint32_t>& indices);

/// Parses "y" or "z"; throws InputError naming `option` otherwise.
UpAxis parse_up_axis(const std::string& text, const char* option);

/// Computes smooth, area-weighted vertex normals from positions and indices,
/// treating vertices at the same position as one (so split UV seams do not
/// show as creases). Degenerate neighbourhoods get (0, 0, 1).
std::vector<glm::vec3> smooth_normals(const std::vector<glm::vec3>& positions,
                                      const std::vector<std::uint32_t>& indices);

}  // namespace terrasprite
