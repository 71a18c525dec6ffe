// SPDX-License-Identifier: MIT
// The hybrid-object walkthrough (Jehaes, Lamotte & Tack, GRAPP 2008, section
// 4): a camera path at human height and low altitude through the object
// scene, with named checkpoints where quality is compared.
#pragma once
#include <functional>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// The default walkthrough over the default object scene (instances within
/// 300 m of the centre): starts at human height (1.7 m) in the south-west
/// corner of the field, walks north-east between the objects, rises to low
/// altitude (about 30 m) over the centre, lands again and ends looking back
/// over the field from 40 m; checkpoints A-E along it. Heights are above
/// `ground(x, y)` (metres; empty: the heightfield's bilinear sample), which
/// should be the surface the terrain is drawn with.
KeyframePath walkthrough_path(const Heightfield& heights,
                              const std::function<double(double, double)>& ground = {});

/// Raises every camera of `path` to at least `min_eye_m` over `ground(x, y)`
/// (between its keys a spline may dip under a ridge of the drawn surface),
/// and brings its near plane within an eighth of its height over that ground
/// (sample_path fits it to the bilinear surface, which may lie far below
/// a coarse grid's). Orientation is kept.
void keep_above_ground(std::vector<Camera>& path,
                       const std::function<double(double, double)>& ground, double min_eye_m = 1.5);

}  // namespace terrasprite
