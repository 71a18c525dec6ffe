// SPDX-License-Identifier: MIT
// The LOD-sprite paper's flight path (Chen, Swan, Kuo, Kaufman 1999, Fig. 7).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace {
constexpr double kPaperFrames = 460.0;
// Relief over extent from which the paper path shows relief well (the
// default synthetic terrain has 2 km over 15.36 km, 0.13), and the closest
// the overview comes (in units of the paper path's distances) over flatter ones.
constexpr double kPaperRelief = 0.12, kMinOverviewScale = 0.35;

// The paper flight with its distances (and clearance) scaled by `scale`.
std::vector<Camera> scaled_paper_path(const Heightfield& h, int frames, double aspect,
                                      double fov_y_deg, double scale) {
  if (frames < 1) throw InputError(fmt::format("frames {}: must be at least 1", frames));
  const double E = h.extent() * scale;
  const glm::dvec3 centre(0.0, 0.0, h.sample(0.0, 0.0));
  std::vector<Camera> path;
  path.reserve(frames);
  for (int f = 0; f < frames; ++f) {
    // Position along the flight in paper frames, so any frame count samples the same path.
    double s = frames == 1 ? 0.0 : f * (kPaperFrames - 1.0) / (frames - 1);
    double elevation = 20.0, azimuth = 0.0, distance = 1.3 * E;
    if (s < 60.0) {
      elevation = 90.0 - 70.0 * s / 60.0;
    } else if (s < 360.0) {
      azimuth = 270.0 * (s - 60.0) / 300.0;
    } else {
      azimuth = 270.0;
      distance = 1.3 * E - (1.3 - 0.35) * E * (s - 360.0) / 99.0;
    }
    // Azimuth 0 puts the camera south of the centre looking north; the orbit runs anticlockwise.
    double el = elevation * kRadiansPerDegree, az = azimuth * kRadiansPerDegree;
    glm::dvec3 dir_to_cam(std::sin(az) * std::cos(el), -std::cos(az) * std::cos(el), std::sin(el));
    glm::dvec3 eye = centre + distance * dir_to_cam;
    double ground = h.sample(eye.x, eye.y);
    eye.z = std::max(eye.z, ground + 0.03 * E);
    // Straight overhead the heading is the orbit's: image top points north.
    Camera c = Camera::look_at(eye, centre, fov_y_deg, aspect, azimuth);
    fit_clip_planes(c, h);
    path.push_back(c);
  }
  return path;
}

}  // namespace

std::vector<Camera> paper_path(const Heightfield& h, int frames, double aspect, double fov_y_deg) {
  return scaled_paper_path(h, frames, aspect, fov_y_deg, 1.0);
}

double overview_scale(const Heightfield& h) {
  const double relief = (h.max_height() - h.min_height()) / std::max(1e-9, h.extent());
  return std::clamp(relief / kPaperRelief, kMinOverviewScale, 1.0);
}

std::vector<Camera> overview_path(const Heightfield& h, int frames, double aspect,
                                  double fov_y_deg) {
  return scaled_paper_path(h, frames, aspect, fov_y_deg, overview_scale(h));
}

std::vector<Camera> make_path(const std::string& spec, const Heightfield& h, int frames,
                              double aspect) {
  if (spec.empty() || spec == "paper") return paper_path(h, frames, aspect);
  if (spec == "low-fast") return low_fast_path(h, frames, aspect);
  if (spec == "overview") return overview_path(h, frames, aspect);
  return load_path_file(spec, h, frames, aspect);
}

}  // namespace terrasprite
