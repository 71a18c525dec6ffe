// SPDX-License-Identifier: MIT
// GL rasterisation of the terrain: the full-resolution reference renderer and
// plain quadtree LOD, one code path for both.
#pragma once
#include <memory>
#include <string>

#include "terrasprite/gl/gl_renderer.h"
#include "terrasprite/raster/scene.h"

namespace terrasprite {

/// How the drape texture is filtered at grazing angles.
enum class DrapeFilter {
  kAuto,       ///< hardware for full resolution (the quality reference), trilinear for LOD
  kHardware,   ///< the GL's 16x anisotropic filtering
  kHand,       ///< up to 8 trilinear taps along the footprint
  kTrilinear,  ///< one trilinear tap, as LOD-sprite's drape fallback
};

struct RasterOptions {
  /// Simple diffuse sun; off by default (the derived texture carries hillshade).
  bool lighting = false;
  /// kAuto: plain LOD filters its drape as the LOD-sprite fallback does
  /// (trilinear), so the two compare on equal terms and neither pays
  /// llvmpipe's anisotropic path (seconds on single grazing frames of the
  /// paper path); trilinear is as close to the anisotropic reference as a
  /// hand filter at a fraction of its time (figures:
  /// docs/results/2026-12-01-lodsprite-drape-filter.md). Full resolution keeps
  /// hardware 16x: it is the quality reference, and its small triangles
  /// never hit that path's stalls.
  DrapeFilter drape_filter = DrapeFilter::kAuto;
  /// Leave out the triangles facing away (down). A camera above the drawn
  /// surface sees none of them (a ray from above meets a face turned towards
  /// it first), so the image is the same and the rasteriser skips their
  /// setup. Off by default: a camera under the drawn surface (a path
  /// at human height over a coarse grid) would see through it.
  bool cull_back_faces = false;
  /// Samples a pixel of the own target (MSAA), 1 to GL_MAX_SAMPLES (4 on
  /// llvmpipe); other counts throw InputError. Edges smaller than a pixel
  /// then show as coverage, not as a staircase that moves with the camera.
  int samples = 1;
};

/// Draws one grid mesh of `scene` with one indexed draw call into a
/// width x height target. quads = 0 draws the full-resolution grid (class
/// "full"); otherwise the coarse grid of `quads` quads per side (class "lod").
/// Frame::ms is wall time to glFinish; gpu_ms from a timer query. `scene`
/// must outlive the renderer. Throws InputError when quads < 0 or exceeds the
/// terrain's quads per side (the value's name in the message is `lod_quads`).
class MeshRenderer : public GlRenderer {
 public:
  MeshRenderer(Scene& scene, int width, int height, int quads = 0, RasterOptions options = {});
  ~MeshRenderer() override;
  Frame draw(const Camera& camera) override;
  std::string name() const override;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace terrasprite
