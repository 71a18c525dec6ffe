// SPDX-License-Identifier: MIT
// Writing a layout back as a scene file (docs/formats.md "Scene files"), so
// the instances a command placed (scattered, grounded) can be read, aimed at
// and reused.
#pragma once
#include <string>

#include "terrasprite/objects/object_layout.h"

namespace terrasprite {

/// The scene-file JSON text of `layout`: every model (file and texture as
/// absolute paths, its options) and every instance listed with its absolute
/// [x, y, z] position (world metres), heading_deg and scale; no scatter.
/// parse_object_layout reads it back to the same instances.
std::string object_layout_json(const ObjectLayout& layout);

}  // namespace terrasprite
