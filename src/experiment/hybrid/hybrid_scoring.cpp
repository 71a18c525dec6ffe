// SPDX-License-Identifier: MIT
// The walkthrough's scores against full geometry: SSIM, PSNR and FLIP over
// the whole frame, and SSIM over the pixels objects cover.
#include <algorithm>
#include <cmath>

#include "hybrid_stages.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite::hybrid_bench {

std::vector<std::uint8_t> object_mask(const std::vector<float>& ref_depth,
                                      const std::vector<float>& test_depth,
                                      const std::vector<float>& terrain) {
  std::vector<std::uint8_t> mask(terrain.size(), 0);
  auto in_front = [](float d, float t) { return std::isfinite(d) && !(d >= t * 0.9995f - 1e-3f); };
  for (std::size_t i = 0; i < mask.size(); ++i)
    mask[i] = (i < ref_depth.size() && in_front(ref_depth[i], terrain[i])) ||
              (i < test_depth.size() && in_front(test_depth[i], terrain[i]));
  return mask;
}

Scorer hybrid_scorer(std::shared_ptr<ScoringState> state) {
  return [state](const Frame& ref, const Frame& test) {
    QualityScore s;
    s.figures[kSsimObjects] = 1.0;
    const bool flip = std::find(state->flip_frames.begin(), state->flip_frames.end(),
                                state->frame) != state->flip_frames.end();
    if (ref.color.rgba == test.color.rgba) {
      s.flip = flip ? 0.0 : -1.0;
      return s;
    }
    quality::SsimOptions so;
    so.channels = false;
    s.psnr = std::min(quality::psnr(ref.color.view(), test.color.view()).rgb, kPsnrCapDb);
    s.ssim = quality::ssim(ref.color.view(), test.color.view(), so).ssim;
    if (state->terrain_depth.size() == std::size_t(ref.width()) * ref.height()) {
      const auto mask = object_mask(ref.depth, test.depth, state->terrain_depth);
      if (std::find(mask.begin(), mask.end(), 1) != mask.end())
        s.figures[kSsimObjects] =
            quality::ssim(ref.color.view(), test.color.view(), so, mask).ssim;
    }
    s.flip = flip ? quality::flip(ref.color.view(), test.color.view()).mean : -1.0;
    return s;
  };
}

}  // namespace terrasprite::hybrid_bench
