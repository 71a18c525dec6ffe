// SPDX-License-Identifier: MIT
// The sprite frame's one draw: the coarse grid with projective texture
// coordinates from the keyframe's matrix.
#pragma once
#include "scene/terrain_gpu.h"
#include "sprite/keyframe.h"

namespace terrasprite {

class SpritePass {
 public:
  SpritePass();
  ~SpritePass();
  SpritePass(const SpritePass&) = delete;
  SpritePass& operator=(const SpritePass&) = delete;
  /// Draws `coarse` (a scene grid mesh of quads_x quads per row) into the
  /// bound target, textured from `key`; quads flagged in key.flags, and
  /// fragments outside the keyframe or on its sky, take the drape texture.
  void draw(TerrainGpu& scene, const GpuMesh& coarse, int quads_x, const Keyframe& key,
            const glm::mat4& view_projection, bool lighting);
  /// Copies `key` into the bound target: colour over the sky, and its depth.
  void composite_keyframe(const Keyframe& key);

 private:
  gl::Program program_;
  gl::Program composite_;
  gl::VertexArray empty_vao_;  // attribute-less draws still need a bound VAO in core profile
  GLint u_vp_, u_key_vp_, u_uv_, u_qx_, u_lighting_;
};

}  // namespace terrasprite
