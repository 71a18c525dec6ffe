// SPDX-License-Identifier: MIT
// Occlusion culling against a depth buffer already drawn (the terrain): an
// object whose bounding sphere lies behind that depth on every pixel its
// projection can touch cannot show, so it costs nothing and needs no
// representation. At human height most of a walkthrough's instances in
// the frustum may be behind a hill (docs/results/2026-12-02-hybrid-occlusion.md).
//
// Conservative by construction: the sphere's exact screen rectangle (its
// tangent planes through the eye), widened by a pixel, is tested against a
// min-depth pyramid, where each texel holds the farthest depth of the block
// under it. A false "hidden" is impossible; a false "visible" only costs time.
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include "terrasprite/camera/camera.h"

namespace terrasprite {

/// Pixels [x0, x1] x [y0, y1], inclusive, in GL window order (row 0 at the
/// bottom, as glReadPixels returns it).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x1 < x0 || y1 < y0; }
};

/// Where a sphere lands on a width x height image of `camera`: the pixel
/// rectangle its projection can touch (exact tangent-plane bounds, one pixel
/// wider each side, clipped to the image) and its nearest point's depth along
/// the view axis, metres. `straddles_near` is true when the sphere reaches the
/// near plane or behind the eye: then no depth test may hide it.
struct SphereOnScreen {
  PixelRect rect;
  double nearest_depth_m = 0;
  bool straddles_near = true;
};
SphereOnScreen sphere_on_screen(const Camera& camera, int width, int height, glm::dvec3 centre_m,
                                double radius_m);

class DepthOcclusion {
 public:
  /// Nothing occludes (every query: visible).
  DepthOcclusion() = default;
  /// `raw` is a reversed-Z zero-to-one depth buffer (near = 1, far and sky =
  /// 0; gl::projection_reversed_z) of width x height, bottom row first, drawn
  /// with `camera`'s near and far planes. Copied into the pyramid. Throws
  /// std::invalid_argument when the size does not match.
  DepthOcclusion(const std::vector<float>& raw, int width, int height, const Camera& camera);

  /// True only if every pixel of `s.rect` already holds a depth nearer than
  /// `s.nearest_depth_m`. False for an empty rectangle, a sphere at the near
  /// plane, or a default-constructed (empty) occluder.
  bool hidden(const SphereOnScreen& s) const;

 private:
  bool nearer(int level, int tx, int ty, const PixelRect& r, float threshold) const;
  int width_ = 0, height_ = 0;
  double near_m_ = 1, far_m_ = 1e5;
  struct Level {
    int w = 0, h = 0;
    std::vector<float> min_depth;  ///< farthest raw depth of the block (reversed Z: smallest)
  };
  std::vector<Level> levels_;  ///< [0] the image, each next one half as wide and tall
};

}  // namespace terrasprite
