// SPDX-License-Identifier: MIT
// The voxel study (`bench voxel`): the CPU ray caster's speed and quality.
// Variants (naive, coherent, multires) at each thread count are rendered
// interleaved frame by frame along a path, so machine noise hits them alike;
// the slow naive variant and the supersampled reference run on every
// score_every-th frame only, and quality is computed outside every timed span.
// Then a static pitch sweep (the paper's Table 1) and a terrain-size sweep.
#pragma once
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/common/image.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/terrain/terrain_info.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite {

/// The variants the study times, in this order; the last is the default.
inline constexpr std::array kVoxelBenchVariants = {VoxelVariant::kNaive, VoxelVariant::kCoherent,
                                                   VoxelVariant::kMultires};

/// A frame the study hands out to be kept (as the bench's PNGs).
enum class VoxelBenchImage {
  kReference,  ///< the supersampled reference, every scored frame
  kMultires,   ///< the default variant at the largest thread count, every scored frame
};

struct VoxelBenchOptions {
  int width = 1920, height = 1080;  ///< pixels
  std::string path = "paper";       ///< make_path's spec: "paper", "low-fast" or a JSON path file
  int frames = 460;                 ///< frames along the path, >= 1
  std::vector<int> threads = {1, 2};  ///< thread counts to time, each >= 1; not empty
  std::vector<double> pitches = {-10, -30, -60, -90};  ///< static pitch sweep, degrees
  int score_every = 20;  ///< naive and the reference on every n-th frame, >= 1
  /// Synthetic terrain sizes (samples a side, 2..8193) of the size sweep; empty: none.
  std::vector<int> terrain_sizes = {1025, 4097};
  int sweep_frames = 46;         ///< frames per terrain in the size sweep (at most `frames`)
  unsigned sweep_seed = 1;       ///< the size sweep's synthetic terrains
  double pixel_voxel_ratio = 1;  ///< VoxelOptions::pixel_voxel_ratio
  int supersample = 2;           ///< reference rays per pixel side
  /// Called outside the timed spans with each frame to keep (frame index along the path).
  std::function<void(VoxelBenchImage, int frame, const Image&)> on_image;
  std::function<void(int done, int total)> progress;
};

/// One variant at the largest thread count (naive: over the scored frames).
struct VoxelVariantResult {
  VoxelVariant variant = VoxelVariant::kMultires;
  int threads = 0;
  std::vector<double> frame_ms;  ///< every frame it drew, in order
  double median_ms = 0, p95_ms = 0;
  double ns_per_pixel = 0;
  /// Naive's median over the scored frames / this variant's over the same frames.
  double speedup_vs_naive = 0;
  /// Median at 1 thread / median at 2; NaN unless both were timed.
  double scaling_2v1 = 0;
  std::vector<std::pair<int, double>> median_ms_by_threads;  ///< (threads, median ms)
  /// Over the scored frames, against the reference: SSIM, SSIM of the
  /// terrain pixels only, PSNR (dB, capped), FLIP.
  Summary ssim, ssim_terrain, psnr, flip;
};

/// One frame along the path: each variant's time and SSIM at the largest
/// thread count, and the reference's time, where drawn.
struct VoxelFrameRow {
  int frame = 0;
  std::array<std::optional<double>, kVoxelBenchVariants.size()> ms, ssim;
  std::optional<double> reference_ms;
};

struct VoxelPitchRow {
  double pitch_deg = 0;
  int threads = 0;
  double median_ms = 0, fps = 0;
};

struct VoxelSizeRow {
  int samples = 0;  ///< terrain samples a side
  int frames = 0;
  double median_ms = 0, p95_ms = 0;
};

struct VoxelBenchResult {
  int hardware_threads = 0;
  TerrainInfo terrain;
  int width = 0, height = 0;
  std::string path;
  int frames = 0;  ///< cameras along the path
  int score_every = 0;
  int scored_frames = 0;  ///< frames the reference drew
  double pixel_voxel_ratio = 1;
  int supersample = 0;
  double reference_median_ms = 0;
  std::vector<int> threads;
  std::vector<VoxelVariantResult> variants;  ///< as kVoxelBenchVariants
  double scaling_2v1 = 0;                    ///< the default variant's; NaN unless timed
  std::vector<VoxelPitchRow> pitch_table;    ///< pitches in order, thread counts within
  std::vector<VoxelSizeRow> terrain_size_sweep;
  std::vector<VoxelFrameRow> per_frame;
};

/// Runs the study over `terrain` (the path is planned over it). Preconditions
/// (the CLI reports them as input errors): the sizes, counts and lists within
/// the ranges stated above. Throws InputError for a bad path spec or file.
VoxelBenchResult run_voxel_bench(const Terrain& terrain, const VoxelBenchOptions& options);

}  // namespace terrasprite
