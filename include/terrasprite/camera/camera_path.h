// SPDX-License-Identifier: MIT
// Camera paths: the LOD-sprite paper's flight (Chen et al. 1999, Fig. 7) and
// JSON keyframe files.
#pragma once
#include <optional>
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

/// A place given in WGS 84 degrees, resolved on a terrain with a CRS.
struct GeoPlace {
  double lon = 0, lat = 0;
  /// Eyes: metres above sea level ("alt_m") or above the ground below
  /// ("agl_m"); targets lie on the ground.
  double height_m = 0;
  bool above_ground = false;
};

/// The paper path with its distances and clearance scaled by
/// overview_scale(h), so a terrain flatter than the paper's (a 100 km DEM
/// with 1 to 4 km of relief) is flown close enough to show its relief: the
/// same flight as paper_path on terrains as steep as the synthetic one.
std::vector<Camera> overview_path(const Heightfield& h, int frames, double aspect,
                                  double fov_y_deg = 60.0);
/// (relief / extent) / 0.12, within 0.35 .. 1 (the default synthetic terrain,
/// 2 km of relief over 15.36 km, gets 1).
double overview_scale(const Heightfield& h);

/// One keyframe of a keyframe path, in world metres (x east, y north, z up,
/// origin at the terrain centre at height 0), or geographic (resolved when
/// the path is sampled on its terrain).
struct PathKeyframe {
  double t = 0;  ///< seconds
  glm::dvec3 position{0.0};
  std::optional<glm::dvec3> target;      ///< looked at; without one, yaw_deg and pitch_deg
  std::optional<GeoPlace> geo_position;  ///< "lon", "lat", "alt_m" | "agl_m": replaces position
  std::optional<GeoPlace> geo_target;    ///< "look_at": {"lon", "lat"}: replaces target
  double yaw_deg = 0, pitch_deg = 0, roll_deg = 0;
  double fov_deg = 60;  ///< vertical field of view, degrees
};

/// A named moment of a path (path file key "checkpoints": [{"name", "t"}]).
struct PathCheckpoint {
  std::string name;
  double t = 0;   ///< seconds, the keyframes' time
  int frame = 0;  ///< the frame nearest t when sampled (checkpoint_frames)
};

/// A keyframe path: at least one keyframe, t strictly increasing, and
/// checkpoints within the keyframes' span (frame 0 until checkpoint_frames).
struct KeyframePath {
  std::string name;  ///< the file, for errors
  std::vector<PathKeyframe> keyframes;
  std::vector<PathCheckpoint> checkpoints;
};

/// Parses path-file JSON (format in docs/formats.md):
/// {"keyframes": [{"t": s, "position": [x,y,z] | "lon", "lat", "alt_m" | "agl_m",
/// "target": [x,y,z] | "look_at": {"lon", "lat"} | "yaw_deg", "pitch_deg",
/// "roll_deg", "fov_deg"}], "checkpoints": [{"name", "t"}]}
/// ("checkpoints" optional). Every number is checked: positions and targets
/// finite and within 1e7 m, t finite (within 1e9 s) and increasing, angles
/// in range, checkpoints named and within the keyframes' span. Throws
/// InputError naming `name` otherwise.
KeyframePath parse_path_json(std::string_view text, const std::string& name);

/// `path` sampled with `frames` frames (>= 1, else InputError) uniformly in t
/// from the first keyframe to the last: Catmull-Rom positions, slerped
/// orientations, fov interpolated, near/far planes fitted to `h`. Geographic
/// keyframes are placed on `h` first (InputError when it has no CRS or a
/// place is off the terrain: targets on it, eyes within one extent of it).
std::vector<Camera> sample_path(const KeyframePath& path, const Heightfield& h, int frames,
                                double aspect);

/// `path`'s checkpoints, each on the frame nearest its time when the path is
/// sampled with `frames` frames (sample_path).
std::vector<PathCheckpoint> checkpoint_frames(const KeyframePath& path, int frames);

/// Reads a JSON path file (parse_path_json's format):
/// {"keyframes": [{"t": s, "position": [x,y,z], "target": [x,y,z] | "yaw_deg",
/// "pitch_deg", "roll_deg", "fov_deg"}]}, sampled as sample_path. Throws
/// InputError naming the file for a missing or malformed file.
std::vector<Camera> load_path_file(const std::string& path, const Heightfield& h, int frames,
                                   double aspect);

/// load_path_file on JSON text already in memory; `name` names it in errors.
std::vector<Camera> path_from_json(std::string_view text, const std::string& name,
                                   const Heightfield& h, int frames, double aspect);

/// A low, fast flight: about 150 m above the ground ahead at 200 m/s, one
/// frame per 1/60 s (so `frames` sets its length: 460 frames fly 1.5 km),
/// weaving gently northwards from 0.2 E south of the centre in banked turns
/// (roll up to 30 degrees), looking 8 degrees down. Near/far planes fitted.
std::vector<Camera> low_fast_path(const Heightfield& h, int frames, double aspect,
                                  double fov_y_deg = 60.0);
/// "paper", "overview", "low-fast" or a JSON file name: dispatches to the four above.
std::vector<Camera> make_path(const std::string& spec, const Heightfield& h, int frames,
                              double aspect);

}  // namespace terrasprite
