// SPDX-License-Identifier: MIT
// The warp study (`bench warp`): post-render warp quality and cost. Along
// each path every frame is rendered once, with a margin; frame b (every
// k_max+1-th) is a real frame, and frames b+1..b+k_max are warped from it by
// each method and scored against their own (cropped) render. Quality is
// computed outside the timed spans.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/experiment/render_mode.h"
#include "terrasprite/terrain/heightfield.h"
#include "terrasprite/terrain/terrain_info.h"
#include "terrasprite/warp/warp.h"

namespace terrasprite {

/// How far the camera moves between a real frame and the frames warped from
/// it, over a whole path (render --warp: frame i is real when i % real_every
/// is 0). A warp reprojects what the real frame saw: turning shows what it did
/// not see (holes, bands at the edges), and moving against nearby ground
/// shows parallax it cannot fill (streaks).
struct WarpStride {
  double max_turn_deg = 0;  ///< largest angle between a real and a warped view direction
  /// Largest eye displacement since the real frame over the real frame's
  /// depth at the image centre (the distance along its view direction to the
  /// ground, or to the far plane).
  double max_move_over_depth = 0;
  int worst_frame = 0;  ///< the warped frame of the larger excess over its limit
  /// Whether warping this far is expected to fail visibly: a turn over a
  /// quarter of the vertical field of view, or a move over a quarter of that depth.
  bool too_far = false;
};
inline constexpr double kWarpMaxTurnOfFov = 0.25, kWarpMaxMoveOverDepth = 0.25;

/// The stride of `path` with one real frame in `real_every` (>= 1).
WarpStride warp_stride(const std::vector<Camera>& path, int real_every, const Heightfield& ground);

/// The methods the study compares, in this order.
inline constexpr std::array kWarpBenchMethods = {WarpMethod::kPoly2, WarpMethod::kDepth};

struct WarpBenchOptions {
  RenderMode renderer = RenderMode::kVoxel;                ///< of the real frames: kVoxel or kFull
  int width = 1920, height = 1080;                         ///< output pixels
  std::vector<std::string> paths = {"paper", "low-fast"};  ///< make_path specs, flown in turn
  int frames = 460;                                        ///< frames along each path, >= 2
  int k_max = 8;         ///< warp up to this many frames past a real one, 1..64
  double margin = 0.05;  ///< real frames this fraction wider on each side, 0..1
  int real_every = 4;    ///< K of the flythrough cost figure, 1..64
  std::function<void(int done, int total)> progress;  ///< per path
};

/// One warped frame scored against its true render, and what the camera did
/// since the real frame (to say where a method breaks).
struct WarpScore {
  double psnr = 0, ssim = 0, flip = 0;  ///< PSNR dB capped at 100
  double psnr_masked = 0;               ///< PSNR over the pixels the warp filled
  double holes = 0;                     ///< hole fraction
  int frame = 0, k = 0;                 ///< frame along the path, frames past the real one
  double turn_deg = 0;                  ///< angle between the real and the warped view direction
  double moved_m = 0;                   ///< eye displacement since the real frame
  double clearance_m = 0;               ///< eye height above the ground below it
};

/// One method along one path: its warp times and scores by k.
struct WarpMethodRun {
  WarpMethod method = WarpMethod::kPoly2;
  std::vector<double> warp_ms;
  std::vector<std::vector<WarpScore>> by_k;  ///< [k - 1]
};

struct WarpPathRun {
  std::string path;
  std::vector<double> real_ms;         ///< every frame's render, with the margin
  std::vector<WarpMethodRun> methods;  ///< as kWarpBenchMethods
};

/// Means over the finite scores at one k (NaN where none).
struct WarpKSummary {
  int k = 0, samples = 0;
  double psnr = 0, ssim = 0, flip = 0, psnr_masked = 0, hole_fraction = 0;
};

/// A method's figures on one path.
struct WarpMethodSummary {
  WarpMethod method = WarpMethod::kPoly2;
  std::string path;
  /// The lowest-PSNR warps (at most 5), lowest first: where the method breaks.
  std::vector<WarpScore> worst;
  double warp_ms_median = 0, real_ms_median = 0;
  double cost_fraction = 0;        ///< warp / real median
  std::vector<WarpKSummary> by_k;  ///< the k with scores, in order
};

/// The flythrough at 60 Hz output with every K-th frame real: the mean cost
/// per output frame, (real + (K - 1) warps) / K, frames not overlapped.
struct WarpFlythrough {
  std::string path;
  WarpMethod method = WarpMethod::kPoly2;
  int real_every = 0;
  double real_ms_mean = 0, real_ms_p99 = 0, warp_ms_mean = 0;
  double mean_ms_per_output_frame = 0;
  bool meets_60hz = false;
};

struct WarpBenchResult {
  std::string device;  ///< the real renderer's
  TerrainInfo terrain;
  int width = 0, height = 0;
  RenderMode renderer = RenderMode::kVoxel;
  std::vector<std::string> paths;
  int frames = 0, k_max = 0;
  int margin_x = 0, margin_y = 0;          ///< pixels each side of the real frames
  std::vector<WarpPathRun> runs;           ///< per path
  std::vector<WarpMethodSummary> methods;  ///< per path, methods within
  std::vector<WarpFlythrough> flythrough;  ///< per path, methods within
};

/// Runs the study over `terrain`. Preconditions (the CLI reports them as
/// input errors): the ranges stated in WarpBenchOptions. Throws InputError
/// for a bad path spec or file (every path is checked before any frame),
/// DeviceError when kFull finds no GL device.
WarpBenchResult run_warp_bench(const Terrain& terrain, const WarpBenchOptions& options);

}  // namespace terrasprite
