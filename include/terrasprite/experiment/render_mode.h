// SPDX-License-Identifier: MIT
// The renderers a flythrough can be drawn with (`render --mode`, `view
// --mode`, the viewer's panel): named, parsed and printed here only.
#pragma once
#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace terrasprite {

enum class RenderMode {
  kFull,    ///< the full-resolution mesh (GL)
  kLod,     ///< a coarse uniform grid of lod_quads per side (GL)
  kSprite,  ///< LOD-sprite: the coarse grid textured with keyframes (GL)
  kVoxel,   ///< the CPU voxel ray caster
};

/// Every mode, in the order of their names and keys 1-4 in the viewer.
inline constexpr std::array kRenderModes = {RenderMode::kFull, RenderMode::kLod,
                                            RenderMode::kSprite, RenderMode::kVoxel};

/// "full", "lod", "sprite", "voxel": a static string.
const char* to_string(RenderMode mode);

/// The names of kRenderModes, in order (for an option's list of choices).
std::vector<std::string> render_mode_names();

/// A mode's name -> the mode. Throws InputError "<option> <text>: unknown
/// mode" for any other text (`option` names the input, e.g. "--mode").
RenderMode parse_render_mode(std::string_view text, const char* option = "--mode");

/// Whether the mode draws with OpenGL (needs a GL context and a Scene).
inline bool is_gl(RenderMode mode) {
  return mode != RenderMode::kVoxel;
}

}  // namespace terrasprite
