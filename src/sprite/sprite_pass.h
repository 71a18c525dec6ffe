// SPDX-License-Identifier: MIT
// The sprite frame's draws: the coarse grid split by class. Quads the
// keyframe can texture take one projective fetch; the rest take the drape
// texture, filtered by hand, through the plain terrain shader.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "raster/terrain_gpu.h"
#include "sprite/keyframe.h"

namespace terrasprite {

class SpritePass {
 public:
  SpritePass();
  ~SpritePass();
  SpritePass(const SpritePass&) = delete;
  SpritePass& operator=(const SpritePass&) = delete;
  /// Draws `coarse` (the GPU copy of `grid`'s mesh_vertices, attribute 0 =
  /// position, 1 = normal) into the bound target, cell by cell as `grid`'s
  /// triangle lists say. Cells with drape[q] == 0 are textured from `key` by
  /// projection (their vertices and centre were visible in it, so every
  /// fragment lands inside it; a fragment on its sky is discarded, where the
  /// coarse mesh sticks out past the true silhouette); the others take the
  /// hand-filtered drape. The split index lists are re-uploaded only when the
  /// grid or `drape` differs from the last call's.
  void draw(TerrainGpu& scene, const GpuMesh& coarse, const CoarseGrid& grid, const Keyframe& key,
            const glm::mat4& view_projection, std::span<const std::uint8_t> drape, bool lighting);
  /// Copies `key` into the bound target: colour over the sky, and its depth;
  /// of a keyframe with a margin (KeyframeFraming) only the view's part,
  /// resampled bilinearly when the keyframe is supersampled.
  void composite_keyframe(const Keyframe& key);
  /// Quads drawn from the keyframe by the last draw().
  int keyframe_quads() const { return key_quads_; }

 private:
  void split(const GpuMesh& coarse, const CoarseGrid& grid, std::span<const std::uint8_t> drape);

  gl::Program program_;  // keyframe-textured quads: one projective fetch
  gl::Program composite_;
  gl::VertexArray empty_vao_;  // attribute-less draws still need a bound VAO in core profile
  GLint u_vp_, u_key_vp_, u_crop_;
  // The coarse mesh's vertices with two index lists: keyframe quads, drape quads.
  GpuMesh key_mesh_, drape_mesh_;
  GLuint source_ = 0;       // vertex buffer the split meshes point at
  std::uint64_t grid_ = 0;  // serial of the grid they were split from
  std::vector<std::uint8_t> last_drape_;
  int key_quads_ = 0;
};

}  // namespace terrasprite
