// SPDX-License-Identifier: MIT
#include "terrasprite/camera/frame.h"

namespace terrasprite {

const char* frame_class_name(FrameClass c) {
  switch (c) {
    case FrameClass::kFull:
      return "full";
    case FrameClass::kLod:
      return "lod";
    case FrameClass::kKey:
      return "key";
    case FrameClass::kSprite:
      return "sprite";
    case FrameClass::kVoxel:
      return "voxel";
    case FrameClass::kWarp:
      return "warp";
    case FrameClass::kReference:
      return "reference";
    case FrameClass::kObjects:
      return "objects";
  }
  return "?";
}

}  // namespace terrasprite
