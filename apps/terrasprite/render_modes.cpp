// SPDX-License-Identifier: MIT
#include "render_modes.h"

#include <fmt/format.h>

#include "terrasprite/common/error.h"

namespace terrasprite::cli {

CoarseMesh parse_mesh(const std::string& text) {
  if (text == "uniform") return CoarseMesh::kUniform;
  if (text == "adaptive") return CoarseMesh::kAdaptive;
  throw InputError(fmt::format("--mesh {}: must be 'uniform' or 'adaptive'", text));
}

void check_mesh_triangles(long long triangles) {
  if (triangles != 0 && triangles < 2)
    throw InputError(fmt::format(
        "--mesh-triangles {}: must be 0 (the uniform grid's 2 x lod-quads^2) or at least 2",
        triangles));
}

}  // namespace terrasprite::cli
