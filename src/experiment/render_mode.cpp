// SPDX-License-Identifier: MIT
#include "terrasprite/experiment/render_mode.h"

#include <fmt/format.h>

#include "terrasprite/common/error.h"

namespace terrasprite {

const char* to_string(RenderMode mode) {
  switch (mode) {
    case RenderMode::kFull:
      return "full";
    case RenderMode::kLod:
      return "lod";
    case RenderMode::kSprite:
      return "sprite";
    case RenderMode::kVoxel:
      return "voxel";
  }
  return "?";
}

std::vector<std::string> render_mode_names() {
  std::vector<std::string> names;
  for (RenderMode m : kRenderModes) names.emplace_back(to_string(m));
  return names;
}

RenderMode parse_render_mode(std::string_view text, const char* option) {
  for (RenderMode m : kRenderModes)
    if (text == to_string(m)) return m;
  throw InputError(fmt::format("{} {}: unknown mode", option, text));
}

}  // namespace terrasprite
