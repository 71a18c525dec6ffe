// SPDX-License-Identifier: MIT
// Shared setup of the hybrid benchmark's tests.
#pragma once
#include <string>

namespace tstest {

/// A small scene file's JSON: 6 scanned teapots and 6 glTF trees scattered
/// (seed 3) over 600 m x 600 m, the models read from `data` (../shared/data).
inline std::string small_hybrid_scene(const std::string& data) {
  return R"({"models": [
    {"name": "teapot", "file": ")" +
         data + R"(/models_scans/teapot.obj", "up": "y", "height_m": 4},
    {"name": "tree", "file": ")" +
         data + R"(/models_kenney_nature/tree_oak_fall.glb", "up": "y", "height_m": 6}],
  "scatter": [{"model": "teapot", "count": 6}, {"model": "tree", "count": 6}],
  "scatter_defaults": {"seed": 3, "region": [-300, -300, 300, 300], "max_slope_deg": 45, "min_spacing_m": 6}})";
}

}  // namespace tstest
