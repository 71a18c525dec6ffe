// SPDX-License-Identifier: MIT
#include "experiment/lodsprite/sprite_pass.h"

#include <algorithm>
#include <string>

#include "experiment/lodsprite/frame_class.h"
#include "terrasprite/common/stats.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite::lodsprite {
namespace {

double ssim_only(const Image& reference, const Image& test) {
  if (reference.rgba == test.rgba) return 1.0;
  quality::SsimOptions so;
  so.channels = false;
  return quality::ssim(reference.view(), test.view(), so).ssim;
}

double psnr_capped(const Image& reference, const Image& test) {
  if (reference.rgba == test.rgba) return kPsnrCapDb;
  return std::min(quality::psnr(reference.view(), test.view()).rgb, kPsnrCapDb);
}

}  // namespace

PassResult sprite_pass(Scene& scene, std::span<const Camera> path, int w, int h,
                       const SpriteOptions& o, const std::vector<Image>& refs, int every) {
  SpriteRenderer r(scene, w, h, o);
  PassResult p;
  std::vector<Image> kept;
  std::vector<double> all_ms, key_ms, sprite_ms;  // draw times, frame order
  Experiment pass;
  pass.add({.renderer = &r,
            .name = "sprite",
            .warmup_draws = 2,  // a keyframe, then a sprite frame; then start afresh
            .read = ReadBack::kColor,
            .after_warmup = [&] { r.reset(); },
            .annotate =
                [&](const Frame& f, FrameResult&) {
                  p.cache_hits += r.last_cache_hit();
                  const bool key = last_frame_class(r) == FrameClass::kKey;
                  p.keyframes += key;
                  all_ms.push_back(f.ms);
                  (key ? key_ms : sprite_ms).push_back(f.ms);
                }});
  ExperimentOptions eo;
  eo.on_frame = [&](int i, const std::string&, const Frame& f) {
    if (i % every == 0) kept.push_back(f.color);
  };
  PathSource cameras(std::vector<Camera>(path.begin(), path.end()));
  eo.keep_frames = false;
  pass.run(cameras, eo);
  p.total_ms = summarize(all_ms).total;
  p.key_median_ms = summarize(key_ms).median;
  p.sprite_median_ms = summarize(sprite_ms).median;
  std::vector<double> ssims, psnrs;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    ssims.push_back(ssim_only(refs[k], kept[k]));
    psnrs.push_back(psnr_capped(refs[k], kept[k]));
  }
  p.mean_ssim = mean(ssims);
  p.mean_psnr = mean(psnrs);
  p.min_ssim = ssims.empty() ? 0.0 : *std::min_element(ssims.begin(), ssims.end());
  return p;
}

int simulate_keyframes(Scene& scene, std::span<const Camera> path, int w, int h,
                       const SpriteOptions& o) {
  SpriteRenderer r(scene, w, h, o);
  int keys = 0;
  for (const Camera& c : path) {
    if (!r.has_keyframe() || r.keyframe_due(r.error(c))) {
      r.make_keyframe(c);
      ++keys;
    }
  }
  return keys;
}

}  // namespace terrasprite::lodsprite
