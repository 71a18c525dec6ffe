// SPDX-License-Identifier: MIT
// A LOD-sprite keyframe: the full-resolution render kept as textures, its
// camera, and what the sprite frames need to know about it.
#pragma once
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "gl/render_target.h"
#include "raster/terrain_gpu.h"
#include "terrasprite/sprite/error_metric.h"

namespace terrasprite {

/// How a keyframe's image relates to the view its sprite frames are drawn
/// at (SpriteOptions::key_margin, key_supersample): the same pose, a field of
/// view wider by a margin on each side, and optionally more pixels per degree.
struct KeyframeFraming {
  double margin = 0;       ///< fraction of the view's width (height) added on each side, >= 0
  double supersample = 1;  ///< keyframe pixels per view pixel, linear, >= 1
  int margin_px(int view_px) const;
  int width(int view_width) const;    ///< the keyframe's, pixels
  int height(int view_height) const;  ///< the keyframe's, pixels
  /// The keyframe's camera for a view of `view_width` x `view_height`.
  Camera camera(const Camera& view, int view_width, int view_height) const;
  bool identity() const { return margin == 0 && supersample == 1; }
};

struct Keyframe {
  gl::RenderTarget
      target;     // colour (transparent black on sky) + depth textures, sampled by sprite frames
  Camera camera;  // the keyframe's own (KeyframeFraming::camera of the view it was asked for)
  glm::mat4 view_projection{1.f};          // reversed-Z GL matrix the keyframe was drawn with
  std::shared_ptr<const CoarseGrid> grid;  // the coarse mesh its sprite frames draw
  KeyframeSamples samples;                 // the error metric's per-quad C' and visibility
  std::vector<std::uint8_t> fallback;      // per quad: 1 = takes the drape texture
  bool valid = false;
  long long used = 0;     // when it last stopped being the current keyframe (cache policy)
  bool contrast = false;  // also read the colour back for the contrast metric
  KeyframeFraming framing;
  int view_width, view_height;  // the sprite frames' image, pixels

  /// `contrast`: capture() also reads the colour back and fills
  /// samples.gradient / samples.deviation (ErrorMetric::kContrast).
  /// A keyframe for sprite frames of `view_width` x `view_height`; its own
  /// image is framing.width(view_width) x framing.height(view_height).
  Keyframe(int view_width, int view_height, bool contrast = false, KeyframeFraming framing = {});
  /// Renders the keyframe camera of the view `camera` (framing.camera) from
  /// the full-resolution mesh into the textures, reads
  /// the depth back (and the colour, for the contrast metric), and classifies the coarse vertices
  /// and quad centres (visible, hidden, outside the view). Drains the pipeline (depth read-back).
  /// `pieces` > 1 draws the mesh in that many batches, each drained before
  /// the next (TerrainGpu::draw_in_pieces): for a keyframe drawn beside
  /// another context's frames on a shared software rasterizer.
  /// `grid` becomes the keyframe's coarse mesh (uniform, or adaptive to `camera`).
  void capture(TerrainGpu& scene, std::shared_ptr<const CoarseGrid> grid, const Camera& camera,
               bool lighting, int pieces = 1);
};

}  // namespace terrasprite
