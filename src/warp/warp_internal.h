// SPDX-License-Identifier: MIT
// The warp methods behind warp_frame(); each fills a WarpedFrame whose
// colour, depth and hole buffers are already sized for the output.
#pragma once
#include "terrasprite/warp.h"
#include "warp/pinhole.h"

namespace terrasprite::warp {

void warp_poly2(const Reference& ref, const Pinhole& out, const WarpOptions& options,
                WarpedFrame& result);
void warp_depth(const Reference& ref, const Reference* second, const Pinhole& out,
                const WarpOptions& options, WarpedFrame& result);

}  // namespace terrasprite::warp
