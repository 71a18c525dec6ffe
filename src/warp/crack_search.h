// SPDX-License-Identifier: MIT
// The depth warp's pixels visited one at a time: cracks and silhouettes
// (output pixels no real pixel landed on, or whose winner lies behind the
// eye) searched by a fixed-point iteration from the farthest neighbouring
// winner to the real-frame point that lands on them (after Mark, McMillan,
// Bishop, "Post-rendering 3D warping", I3D 1997: reconstruction); holes
// read from a second reference; background extension along the row.
#pragma once
#include <cstdint>
#include <vector>

#include "terrasprite/warp/warp.h"
#include "warp/pinhole.h"
#include "warp/splat.h"

namespace terrasprite::warp {

/// Resolves single output pixels of `result` from the splat's winners
/// (`win`, `win_depth`: splat()'s, out.w x out.h). Each call writes the
/// pixel's colour, depth, hole flag (and sources with keep_sources). Cheap to
/// copy; one per task.
struct Resolver {
  const Reference& ref;
  const Reference* second;  ///< fills the primary's holes; may be null
  const Pinhole& out;
  const SplatMap& map;
  const std::vector<std::uint32_t>& win;
  const std::vector<float>& win_depth;
  bool keep_sources;
  WarpedFrame& result;

  /// Pixel (px, py) with a winner whose landing point says where to read;
  /// false when the winner lies behind the new eye.
  bool winner(std::uint32_t key, int px, int py);
  /// Pixel (px, py) without a usable winner: iterate from the farthest
  /// neighbouring winner to the real-frame point that lands on it, or sky
  /// where the real frame sees sky in its direction; else a hole, read from
  /// the second reference when there is one. False when neither reference
  /// sees it (the caller extends the background).
  bool search(int px, int py);
  /// A pixel neither the real frame's surfaces nor its sky cover; `nb` its
  /// farthest neighbouring winner (or kEmpty). True when the second
  /// reference fills it.
  bool hole(int px, int py, std::uint32_t nb);

 private:
  bool from_winner(std::uint32_t key, double x, double y, double& sx, double& sy, float& zt) const;
  std::uint32_t farthest_neighbour(int px, int py) const;
  void write(std::size_t at, double sx, double sy, double zt);
  bool from_second(int px, int py, std::uint32_t nb, std::uint8_t* rgba);
};

/// Fills the pixels of row y where miss[x] != 0 from the farther of their
/// resolved neighbours on the row (background extension); a row with none
/// stays as it is.
void extend_background(WarpedFrame& r, int y, const std::uint8_t* miss);

}  // namespace terrasprite::warp
