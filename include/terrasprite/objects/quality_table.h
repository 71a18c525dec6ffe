// SPDX-License-Identifier: MIT
// Measured quality tables of a model's representations (Jehaes, Lamotte,
// Tack, GRAPP 2008, section 3.2): each representation rendered beside the
// full model from many viewing angles and on-screen sizes, scored with PSNR
// and SSIM on the pixels either image covers, over the sky colour.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/objects/object_renderer.h"

namespace terrasprite {

/// On-screen sizes a table may sample, px. 4 is where an instance is a few
/// pixels (the walkthrough's far instances: a table whose smallest size is
/// 16 px predicts them from the 16 px samples).
constexpr int kMinTableSizePx = 4, kMaxTableSizePx = 2048;
/// The finest view step a table samples, degrees: at 1 degree a table
/// already draws about 360 x 90 views per size and heading; a finer step only
/// multiplies the time and the memory.
constexpr double kMinTableAngleStepDeg = 1.0;

struct TableOptions {
  std::vector<ObjectKind> kinds{ObjectKind::kMesh, ObjectKind::kRelief, ObjectKind::kOctahedral};
  std::vector<int> resolutions{16, 32, 64, 128, 256, 512};  ///< impostor texels per face / view
  std::vector<int> sizes_px{400, 200, 100, 50, 25};         ///< on-screen bounding-sphere diameter
  /// phi in [0, 360), theta in [0, 90] (or [0, 180]); straight above (theta 0)
  /// and below (180) are sampled once, at phi 0.
  double angle_step_deg = 30.0;  ///< kMinTableAngleStepDeg..180
  bool full_sphere = false;      ///< theta up to 180 (from below too)
  /// Compass headings, degrees in [0, 360), the model is drawn at. The sun
  /// is fixed in the world and an instance's heading turns its normals, so
  /// the heading says from which side the model is lit; phi and theta stay
  /// in the model's frame. {0}: one light, as before.
  std::vector<double> headings_deg{0.0};
  int views = 12;            ///< octahedral views per side
  int timing_instances = 1;  ///< instances drawn (3 times, median) to time a representation
  /// Samples a pixel (MSAA) of every image drawn, the reference's included:
  /// 1 to GL_MAX_SAMPLES, as the scene that uses the table draws.
  int samples = 1;
  std::vector<double> ssim_targets{0.90, 0.95, 0.98, 0.99};
  std::vector<double> psnr_targets{20, 25, 30, 35};
};

struct QualitySample {
  double phi_deg = 0;    ///< azimuth of the camera around the object
  double theta_deg = 0;  ///< 0 = from straight above, 90 = horizontal
  int size_px = 0;
  double psnr = 0;         ///< RGB PSNR in dB, masked; +inf when identical
  double ssim = 0;         ///< Wang SSIM on luma, masked
  double heading_deg = 0;  ///< the model's compass heading (its side to the sun)
};

struct SizeCost {
  int size_px = 0;
  double ms_per_instance = 0;  ///< median draw time per instance, pipeline drained
};

struct RepresentationQuality {
  Representation rep;
  long long triangles = 0;     ///< per instance
  std::size_t bytes = 0;       ///< GPU memory of the representation
  double error_m = 0;          ///< LOD level's geometric error (meshes only)
  double build_ms = 0;         ///< building the impostor (0 for meshes)
  double ms_per_instance = 0;  ///< at the middle size of the sweep
  std::vector<SizeCost> cost;  ///< per size
  std::vector<QualitySample> samples;
  /// Mean of `metric` ("ssim" or "psnr"; psnr capped at 100 dB) over the samples at `size_px`.
  double mean(const std::string& metric, int size_px) const;
};

/// One cell of the paper's Table 1: the lowest impostor resolution (or the
/// coarsest LOD level) whose mean quality at `size_px` reaches `target`.
struct TableEntry {
  ObjectKind kind = ObjectKind::kRelief;
  int size_px = 0;
  std::string metric;  ///< "ssim" or "psnr"
  double target = 0;
  std::optional<int> choice;  ///< resolution (impostors) or level (meshes); none reaches it
};

struct QualityTable {
  std::string model;
  long long triangles = 0;
  std::vector<RepresentationQuality> representations;
  std::vector<TableEntry> table;
  double build_ms = 0;  ///< wall time of measure_quality_table
};

/// The camera of a table's sample: on a sphere around the model's centre at
/// (phi, theta) in the model's frame, far enough that the bounding sphere
/// spans `size_px` of an image `side` px square, for the model at the origin
/// turned to `heading_deg` (ObjectInstance{{}, heading_deg, 1}).
Camera table_camera(const Model& m, double phi_deg, double theta_deg, int size_px, int side,
                    double heading_deg);

/// Renders and scores every representation of `model` (levels of its chain
/// for kMesh, each resolution for the impostors) at every view and size.
/// Needs a current GlContext. `progress(done, total)` is called per view.
/// Throws InputError for an empty list, a size under 4 or over 2048 px,
/// an angle step outside (0, 180], or a heading outside [0, 360) or repeated.
QualityTable measure_quality_table(GlModel& model, const TableOptions& options,
                                   const std::function<void(int, int)>& progress = {});

/// Throws InputError naming `option` for an empty list, a heading outside
/// [0, 360) or one given twice.
void check_headings(const std::vector<double>& headings_deg, const char* option);

/// Table 1 from measured representations.
std::vector<TableEntry> derive_table(const std::vector<RepresentationQuality>& reps,
                                     const TableOptions& options);

}  // namespace terrasprite
