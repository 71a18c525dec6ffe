// SPDX-License-Identifier: MIT
// The terrain's GPU side: drape texture, grid meshes per level and the plain
// terrain shader, shared by the raster and sprite renderers through Scene.
#pragma once
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <vector>

#include "gl/gl_objects.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/terrain/grid_mesh.h"

namespace terrasprite {

/// A grid mesh in GPU buffers: attribute 0 = position (vec3, metres),
/// attribute 1 = normal (vec3), one uint32 index list. Grids above 4097 x 4097
/// samples are split into `parts` (tiles sharing their border samples), each
/// drawn with its own call; `triangles` then counts all parts.
/// How the plain terrain shader filters the drape texture.
enum class DrapeSampling {
  kHardware,   ///< the texture's own 16x anisotropic filtering (the quality reference)
  kHand,       ///< up to 8 trilinear taps along the footprint (kHandFilterGlsl)
  kTrilinear,  ///< one trilinear tap: llvmpipe's fast, per-quad path
};

struct GpuMesh {
  std::vector<GpuMesh> parts;
  gl::VertexArray vao;
  gl::Buffer vertices;
  gl::Buffer indices;
  GLsizei index_count = 0;
  long long triangles = 0;
  int columns = 0, rows = 0;
};

/// Uploads `cpu` into `g`'s buffers (immutable storage: once per GpuMesh).
void upload_grid_mesh(GpuMesh& g, const GridMesh& cpu);

/// Owned by a Scene; needs its GL context current. Keeps a reference to `terrain`.
class TerrainGpu {
 public:
  /// Uploads the drape texture. Throws InputError when it exceeds GL_MAX_TEXTURE_SIZE.
  explicit TerrainGpu(const Terrain& terrain);
  ~TerrainGpu();
  TerrainGpu(const TerrainGpu&) = delete;
  TerrainGpu& operator=(const TerrainGpu&) = delete;
  const Terrain& terrain() const { return terrain_; }
  /// The mesh of `quads` quads per side (0 = full), uploaded on first use.
  /// Throws InputError when it would need more than 4 GiB of buffers.
  const GpuMesh& mesh(int quads);
  /// Draws `m` with the plain terrain shader: drape texture by world
  /// position, filtered as `sampling` says, optional sun lighting. The
  /// target must be bound. With `cull_back_faces` the triangles facing down
  /// are not rasterised (RasterOptions::cull_back_faces); face culling is
  /// off again on return.
  void draw(const GpuMesh& m, const glm::mat4& view_projection, bool lighting,
            DrapeSampling sampling = DrapeSampling::kHardware, bool cull_back_faces = false);
  /// draw() with the hardware filter, split into about `pieces` draws of
  /// consecutive triangles with `between()` called after each (a keyframe on
  /// a second context calls glFinish there: llvmpipe has one rasterizer for
  /// all contexts, taking whole flushed batches in turn, so small batches let
  /// the other context's frames through).
  void draw_in_pieces(const GpuMesh& m, const glm::mat4& view_projection, bool lighting, int pieces,
                      const std::function<void()>& between);
  /// Uniforms mapping world (x, y) to drape texture coordinates: uv = xy * scale + offset.
  glm::vec4 uv_transform() const;
  GLuint drape() const { return drape_.id(); }
  /// A trilinear-only sampler for the drape (hand-filtered paths bind it).
  GLuint trilinear_sampler() const { return trilinear_; }
  /// Shading of every later draw (every renderer on this scene). kRich
  /// uploads the heights as a texture on first use; throws InputError when
  /// they exceed GL_MAX_TEXTURE_SIZE.
  void set_shading(TerrainShading shading);
  TerrainShading shading() const { return shading_; }

 private:
  void use_program(const glm::mat4& view_projection, bool lighting, DrapeSampling sampling);

  const Terrain& terrain_;
  gl::Texture drape_{GL_TEXTURE_2D};
  // [rich][hand]: plain or rich shading; drape by hardware or by hand.
  gl::Program programs_[2][2];
  std::optional<gl::Texture> heights_;  // R32F heights for kRich, made on first need
  TerrainShading shading_ = TerrainShading::kPlain;
  GLuint trilinear_ = 0;           // sampler object: trilinear, no hardware anisotropy
  std::map<int, GpuMesh> meshes_;  // by quads per side; 0 = full resolution
};

/// GLSL helper text: `vec2 drape_uv(vec2 world_xy)` using uniform vec4 u_uv (scale.xy, offset.xy).
extern const char* const kDrapeUvGlsl;
/// GLSL helper text: `vec4 drape_hand_filtered(sampler2D, vec2 uv, vec2 dFdx, vec2 dFdy)`:
/// up to 8 trilinear taps along the footprint's major axis.
extern const char* const kHandFilterGlsl;

}  // namespace terrasprite
