// SPDX-License-Identifier: MIT
// The interface every renderer implements.
#pragma once
#include <string>

#include "terrasprite/camera.h"
#include "terrasprite/frame.h"

namespace terrasprite {

/// Sky colour every renderer clears to (sRGB, 0..255), so images compare.
inline constexpr unsigned char kSkyColor[3] = {150, 185, 225};

/// Renders a camera view into a Frame of the renderer's fixed size.
/// Frame::ms covers only the rendering work (DESIGN.md timing rules);
/// read-back of colour and depth happens afterwards and is not counted.
class Renderer {
 public:
  virtual ~Renderer() = default;
  virtual Frame render(const Camera& camera) = 0;
  virtual std::string name() const = 0;
};

}  // namespace terrasprite
