// SPDX-License-Identifier: MIT
// The class of the frame a SpriteRenderer drew last, read from its typed
// state (a keyframe is a draw with a trigger; a cache reuse is a sprite frame).
#pragma once
#include "terrasprite/experiment/lodsprite/lodsprite_result.h"
#include "terrasprite/sprite/sprite_renderer.h"

namespace terrasprite::lodsprite {

inline FrameClass last_frame_class(const SpriteRenderer& r) {
  return r.last_trigger() ? FrameClass::kKey : FrameClass::kSprite;
}

}  // namespace terrasprite::lodsprite
