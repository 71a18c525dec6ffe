// SPDX-License-Identifier: MIT
// Objects on the terrain drawn with OpenGL: a model's LOD meshes and its two
// image-based impostors (relief texture, octahedral), instanced, lit by the
// sun (Lambert + ambient, the terrain's own light).
#pragma once
#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/objects/lod_chain.h"
#include "terrasprite/objects/model.h"
#include "terrasprite/objects/representation_cache.h"

namespace terrasprite {

/// One placed copy of a model: its base point in world metres, its compass
/// heading (degrees clockwise from north; the model's +y axis points there)
/// and a uniform scale on the model's own metres.
struct ObjectInstance {
  glm::dvec3 position{0.0};
  double heading_deg = 0.0;
  double scale = 1.0;
};

/// A model vector turned by a compass heading (radians, clockwise seen from
/// above), as the object shaders turn an instance's positions and normals.
inline glm::dvec3 heading_rotate(glm::dvec3 v, double heading_rad) {
  const double c = std::cos(heading_rad), s = std::sin(heading_rad);
  return {c * v.x + s * v.y, -s * v.x + c * v.y, v.z};
}

enum class ObjectKind { kMesh, kRelief, kOctahedral };

/// Parses "pm" | "mesh", "relief", "octahedral"; throws InputError naming `option`.
ObjectKind parse_object_kind(const std::string& text, const char* option);
/// "pm", "relief" or "octahedral" (the JSON names).
const char* object_kind_name(ObjectKind kind);

/// Which representation to draw: a LOD level (kMesh), or an impostor at
/// `resolution` texels per face (kRelief) or per view (kOctahedral, `views`
/// x `views` views on the hemi-octahedron).
struct Representation {
  ObjectKind kind = ObjectKind::kMesh;
  int level = 0;
  int resolution = 64;
  int views = 12;
};

/// A model resident on the GPU: every level of its LOD chain, and impostors
/// built on first use (each built from level 0, unlit: albedo, normal and
/// depth, lit when drawn). Needs a current GlContext for its whole life.
/// Impostor resolutions are 16 to 512 (views 2 to 32); others throw InputError.
/// With an enabled `cache`, an impostor's textures are read from it when an
/// entry is there (no capture), else captured, read back once and stored.
class GlModel {
 public:
  GlModel(const Model& model, std::vector<LodLevel> chain, RepresentationCache cache = {});
  ~GlModel();
  GlModel(const GlModel&) = delete;
  GlModel& operator=(const GlModel&) = delete;

  const Model& model() const;
  const std::vector<LodLevel>& chain() const;
  const RepresentationCache& cache() const;
  /// Builds the impostor now (else the first draw does). Changes the bound
  /// framebuffer, viewport and depth state: bind the target again afterwards.
  void prepare(const Representation& rep);
  /// Triangles submitted per instance (impostors: the box's 12 or the quad's 2).
  long long triangles(const Representation& rep) const;
  /// GPU memory of the representation: vertex + index buffers, or textures.
  std::size_t bytes(const Representation& rep);

  /// Model metres above an instance's base (times its scale) from which the
  /// camera sees no back face of LOD level `level`: the model's top, where
  /// back faces covered at most 0.5% of the level's pixels in each of 12
  /// views above it, drawn when the model was made. No camera there is
  /// inside a closed part; only an opening facing up (a cup) or a face wound
  /// the wrong way would show one. Mesh draws cull the back faces of
  /// double-sided parts for instances the camera is above it. +inf where a
  /// view showed back faces or the level has no double-sided part. Throws
  /// InputError for a level outside the chain.
  double back_faces_hidden_above(int level) const;
  /// Turns that culling off (draws every double-sided part with its back
  /// faces, as the file says) or on again (the default): for comparisons
  /// and for a cost calibration that times each level both ways.
  void set_cull_hidden_back_faces(bool on);
  bool culls_hidden_back_faces() const;
  /// Whether a draw of `instance` as `rep` from `camera` culls those back
  /// faces: a mesh level with a finite back_faces_hidden_above, the culling
  /// on, and the camera higher than the instance's base plus its scale times
  /// that height. The draw and the cost model's prediction both ask this.
  bool culls_back_faces(const Representation& rep, const ObjectInstance& instance,
                        const Camera& camera) const;

  /// Draws `instances` with one instanced draw per part into the currently
  /// bound framebuffer, which must use the RenderTarget conventions
  /// (reversed-Z float depth, GL_GREATER, zero-to-one clip control). Writes
  /// colour and true depth; depth-tests against what is there.
  void draw(const Representation& rep, std::span<const ObjectInstance> instances,
            const Camera& camera);

  /// One representation and the instances drawn with it.
  struct Group {
    Representation rep;
    std::span<const ObjectInstance> instances;
  };
  /// Draws every group as `draw` does, their instances written to the GPU
  /// in one upload first. Writing the instance buffer while a queued draw
  /// reads it makes llvmpipe drain its pipeline: one group at a time, every
  /// group after a model's first waited for the previous one to finish.
  void draw(std::span<const Group> groups, const Camera& camera);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace terrasprite
