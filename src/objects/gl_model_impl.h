// SPDX-License-Identifier: MIT
// GlModel's insides, shared by the mesh and impostor drawing files.
#pragma once
#include <map>
#include <optional>

#include "gl/gl_objects.h"
#include "terrasprite/objects/object_renderer.h"

namespace terrasprite {

namespace objects {

/// Instance attributes: location 3 = vec4(position xyz, heading radians),
/// location 4 = vec4(scale, 0, 0, 0); binding 1, divisor 1.
struct GpuInstance {
  float position_heading[4];
  float scale[4];
};

struct GpuLevel {
  gl::VertexArray vao;
  gl::Buffer vertices;  // interleaved position, normal, uv: 8 floats
  gl::Buffer indices;
  std::vector<MeshPart> parts;
  std::size_t bytes = 0;
};

/// Six colour + geometry images of the object seen orthographically through
/// the faces of its bounding box (layers +x, -x, +y, -y, +z, -z).
struct ReliefImpostor {
  gl::Texture albedo{GL_TEXTURE_2D_ARRAY};    // RGBA8: base colour, alpha = coverage
  gl::Texture geometry{GL_TEXTURE_2D_ARRAY};  // RGBA16F: object-space normal, depth in [0, 1]
  int resolution = 0;
  std::size_t bytes = 0;
};

/// views x views orthographic views on the upper hemi-octahedron, one atlas.
struct OctahedralImpostor {
  gl::Texture albedo{GL_TEXTURE_2D};  // RGBA8: base colour, alpha = coverage
  gl::Texture geometry{
      GL_TEXTURE_2D};  // RGBA8: octahedron-encoded normal, 16-bit depth (capture.h)
  int resolution = 0, views = 0;
  float radius = 0;  ///< model metres: the views frame the sphere around the centre through the
                     ///< farthest vertex
  std::size_t bytes = 0;
};

/// GLSL: instance attributes, heading rotation and the sun.
extern const char* const kObjectGlsl;
/// GLSL: vec3 sun_lit(vec3 albedo, vec3 normal), the terrain's sun (Lambert + ambient).
extern const char* const kSunGlsl;
/// The relief impostor's box: the model's bounds grown by 0.5% of the diagonal.
void relief_box(const Model& m, glm::vec3& lo, glm::vec3& hi);

}  // namespace objects

struct GlModel::Impl {
  Model model;
  std::vector<LodLevel> chain;
  RepresentationCache cache;
  std::vector<objects::GpuLevel> levels;
  std::vector<gl::Texture> textures;
  gl::Program mesh_program;
  gl::Program capture_program;  // unlit albedo + normal + depth, for impostor building
  gl::Program relief_program;
  gl::Program octahedral_program;
  gl::VertexArray instance_vao;  // impostors: instance attributes only
  std::optional<gl::Buffer> instance_buffer;
  std::size_t instance_capacity = 0;
  std::vector<std::uint8_t> uploaded;  // what instance_buffer holds (GpuInstance bytes)
  std::map<int, objects::ReliefImpostor> relief;
  std::map<std::pair<int, int>, objects::OctahedralImpostor> octahedral;

  /// Uploads the instances (skipped when the buffer holds them already).
  void upload_instances(std::span<const ObjectInstance> instances);
  /// Uploads the instances; binds the buffer to `vao`'s binding 1.
  void upload_instances(std::span<const ObjectInstance> instances, GLuint vao);
  void bind_instances(GLuint vao);
  void attach_instance_attributes(GLuint vao);
  /// Draws level `level` with `program` (its u_vp set by the caller): one
  /// instanced draw per part, material colour and texture bound. Instances
  /// `first` to `first + count - 1` of the bound instance buffer.
  /// `cull_all` culls back faces of double-sided parts too (instances the
  /// camera is above back_faces_hidden_above).
  void draw_level_parts(int level, GLuint program, GLsizei count, GLuint first = 0,
                        bool cull_all = false);
  /// Per level, model metres above the base: GlModel::back_faces_hidden_above.
  std::vector<double> back_faces_hidden_above;
  bool cull_hidden_back_faces = true;
  /// back_face_check.cpp: back_faces_hidden_above for every level, drawn
  /// once when the model is made.
  std::vector<double> find_back_faces_hidden_above();

  objects::ReliefImpostor& relief_impostor(int resolution);
  objects::OctahedralImpostor& octahedral_impostor(int resolution, int views);
  void draw_relief(const objects::ReliefImpostor& r, GLsizei count, GLuint first,
                   const Camera& camera);
  void draw_octahedral(const objects::OctahedralImpostor& o, GLsizei count, GLuint first,
                       const Camera& camera);
};

namespace objects {
/// Programs of the impostors (compiled once per GlModel).
gl::Program make_capture_program();
gl::Program make_relief_program();
gl::Program make_octahedral_program();
/// The mesh vertex stage with a fragment stage that writes white for front
/// faces and red for back faces (back_face_check.cpp).
gl::Program make_back_face_mark_program();
}  // namespace objects

}  // namespace terrasprite
