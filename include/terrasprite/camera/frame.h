// SPDX-License-Identifier: MIT
// One rendered frame: colour, depth and what it cost.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/common/image.h"

namespace terrasprite {

/// Sky colour every renderer clears to (sRGB, 0..255), so images compare.
inline constexpr unsigned char kSkyColor[3] = {150, 185, 225};

/// What a renderer's read_back copies to the CPU. Flags: combine with |.
enum class ReadBack : unsigned { kNone = 0, kColor = 1, kDepth = 2, kColorDepth = 3 };
constexpr ReadBack operator|(ReadBack a, ReadBack b) {
  return ReadBack(unsigned(a) | unsigned(b));
}
constexpr bool has(ReadBack set, ReadBack flag) {
  return (unsigned(set) & unsigned(flag)) != 0;
}

/// What drew a frame: the renderer, and for LOD-sprite whether it is a
/// keyframe (kKey), a sprite (kSprite) or plain LOD before the first keyframe
/// (kLod). kReference: the voxel caster's supersampled reference; kObjects:
/// a hybrid-objects frame.
enum class FrameClass : std::uint8_t {
  kFull,
  kLod,
  kKey,
  kSprite,
  kVoxel,
  kWarp,
  kReference,
  kObjects
};
/// "full", "lod", "key", "sprite", "voxel", "warp", "reference", "objects".
const char* frame_class_name(FrameClass c);

/// A rendered frame: what it cost, the camera it was drawn with and, once read
/// back, its colour and linear depth. Rows top to bottom. A renderer's draw()
/// fills everything but colour and depth (a CPU renderer fills those too);
/// read_back() adds them.
struct Frame {
  Image color;  ///< RGBA8, alpha 255; empty until read back
  std::vector<float>
      depth;        ///< width*height, metres along the view axis; +inf = sky; empty if not read
  double ms = 0.0;  ///< rendering work, wall clock, pipeline drained (read-back excluded)
  double gpu_ms = -1.0;             ///< GL timer-query time, or -1 when unavailable
  long long triangles = 0;          ///< triangles submitted (0 for non-raster renderers)
  int width_px = 0, height_px = 0;  ///< the drawn image's size, also before read-back
  FrameClass cls = FrameClass::kFull;
  /// The camera the frame was rendered with (its view() and projection(),
  /// near/far included), so a later stage (warp, quality) can reproject it.
  Camera camera;

  static constexpr float kSky = std::numeric_limits<float>::infinity();
  int width() const { return width_px > 0 ? width_px : color.width; }
  int height() const { return height_px > 0 ? height_px : color.height; }

  /// Readies this frame for a writer of every colour and depth pixel at
  /// `w` x `h`: buffers that already hold that many pixels are kept as they
  /// are (not cleared: reusing them spares a flythrough an allocation and
  /// its page faults each frame), others are replaced. Clears the colour's
  /// georeference and the GL-only fields (gpu_ms, triangles, width_px,
  /// height_px); cls, camera and ms are the writer's to set.
  void prepare_for_overwrite(int w, int h) {
    const std::size_t n = static_cast<std::size_t>(w) * h;
    if (color.width != w || color.height != h || color.rgba.size() != n * 4) color = Image(w, h);
    color.geo.reset();
    depth.resize(n);
    gpu_ms = -1.0;
    triangles = 0;
    width_px = height_px = 0;
  }
};

}  // namespace terrasprite
