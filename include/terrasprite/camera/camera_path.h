// SPDX-License-Identifier: MIT
// Camera paths: the LOD-sprite paper's flight (Chen et al. 1999, Fig. 7) and
// JSON keyframe files.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// The paper path over `h`, sampled with `frames` frames (>= 1; the paper uses
/// 460). Distances in units of the terrain extent E, always looking at the
/// terrain centre: paper frames 0-59 tilt from straight overhead (pitch -90)
/// to 20 degrees elevation at 1.3 E; 60-359 orbit 270 degrees at that
/// elevation and distance; 360-459 move in along the view to 0.35 E. Another
/// frame count samples the same flight. The camera keeps at least 0.03 E above
/// the ground below it. Near/far planes are fitted per frame.
std::vector<Camera> paper_path(const Heightfield& h, int frames, double aspect,
                               double fov_y_deg = 60.0);

/// Reads a JSON path file (format in the README):
/// {"keyframes": [{"t": s, "position": [x,y,z], "target": [x,y,z] | "yaw_deg",
/// "pitch_deg", "roll_deg", "fov_deg"}]} in world metres (x east, y north,
/// z up, origin at the terrain centre at height 0). Samples `frames` frames
/// uniformly in t (Catmull-Rom positions, slerped orientations).
/// Throws InputError naming the file for a missing or malformed file.
std::vector<Camera> load_path_file(const std::string& path, const Heightfield& h, int frames,
                                   double aspect);

/// load_path_file on JSON text already in memory; `name` names it in errors.
/// Every number is checked: positions and targets finite and within 1e7 m,
/// t finite (within 1e9 s) and increasing, angles in range.
std::vector<Camera> path_from_json(std::string_view text, const std::string& name,
                                   const Heightfield& h, int frames, double aspect);

/// A low, fast flight: about 150 m above the ground ahead at 200 m/s, one
/// frame per 1/60 s (so `frames` sets its length: 460 frames fly 1.5 km),
/// weaving gently northwards from 0.2 E south of the centre in banked turns
/// (roll up to 30 degrees), looking 8 degrees down. Near/far planes fitted.
std::vector<Camera> low_fast_path(const Heightfield& h, int frames, double aspect,
                                  double fov_y_deg = 60.0);
/// "paper", "low-fast" or a JSON file name: dispatches to the three above.
std::vector<Camera> make_path(const std::string& spec, const Heightfield& h, int frames,
                              double aspect);

}  // namespace terrasprite
