// SPDX-License-Identifier: MIT
// The warp methods behind warp_frame(); each writes every pixel of a
// WarpedFrame whose colour, depth, hole (and source) buffers are already
// sized for the output (they hold the previous call's values: nothing is
// cleared for them).
#pragma once
#include <cstdint>
#include <vector>

#include "terrasprite/warp/warp.h"
#include "warp/pinhole.h"

namespace terrasprite {

/// Per-Warper scratch the depth warp reuses between calls.
struct Warper::Scratch {
  std::vector<std::uint32_t> win;       ///< splat winners (real-pixel keys), one per output pixel
  std::vector<float> win_depth;         ///< their new-camera depths (where win holds a key)
  std::vector<std::int32_t> span_rows;  ///< per real-frame span: output rows it lands in
};

namespace warp {

void warp_poly2(const Reference& ref, const Pinhole& out, const WarpOptions& options,
                WarpedFrame& result);
void warp_depth(const Reference& ref, const Reference* second, const Pinhole& out,
                const WarpOptions& options, WarpedFrame& result, Warper::Scratch& scratch);

}  // namespace warp
}  // namespace terrasprite
