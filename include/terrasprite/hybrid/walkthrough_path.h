// SPDX-License-Identifier: MIT
// The hybrid-object walkthrough (Jehaes, Lamotte & Tack, GRAPP 2008, section
// 4): a camera path at human height and low altitude through the object
// scene, with named checkpoints where quality is compared.
#pragma once
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// A named moment of a path (path file key "checkpoints": [{"name", "t"}]).
struct PathCheckpoint {
  std::string name;
  double t = 0;   ///< seconds, the keyframes' time
  int frame = 0;  ///< the frame nearest t when sampled (checkpoints_of)
};

/// The checkpoints of a JSON path file's text (none when it has no
/// "checkpoints" key), each placed on the frame nearest its time when the
/// path is sampled with `frames` frames uniformly from the first keyframe's
/// t to the last's. Throws InputError naming `name` for a checkpoint without
/// a name, a t that is not a number, or a t outside the keyframes' span.
std::vector<PathCheckpoint> checkpoints_of(std::string_view json_text, const std::string& name,
                                           int frames);

/// The default walkthrough over the default object scene (instances within
/// 300 m of the centre) as path-file JSON: starts at human height (1.7 m) in
/// the south-west corner of the field, walks north-east between the objects,
/// rises to low altitude (about 30 m) over the centre, lands again and ends
/// looking back over the field from 40 m; checkpoints A-E along it.
/// Heights are above `ground(x, y)` (metres; empty: the heightfield's
/// bilinear sample), which should be the surface the terrain is drawn with.
std::string walkthrough_path_json(const Heightfield& heights,
                                  const std::function<double(double, double)>& ground = {});

/// Raises every camera of `path` to at least `min_eye_m` over `ground(x, y)`
/// (between its keys a spline may dip under a ridge of the drawn surface),
/// and brings its near plane within an eighth of its height over that ground
/// (path_from_json fits it to the bilinear surface, which may lie far below
/// a coarse grid's). Orientation is kept.
void keep_above_ground(std::vector<Camera>& path,
                       const std::function<double(double, double)>& ground, double min_eye_m = 1.5);

}  // namespace terrasprite
