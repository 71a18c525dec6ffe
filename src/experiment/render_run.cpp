// SPDX-License-Identifier: MIT
#include "terrasprite/experiment/render_run.h"

#include "terrasprite/common/stats.h"
#include "terrasprite/experiment/flythrough.h"

namespace terrasprite {

RenderRunResult run_render(Renderer& renderer, std::span<const Camera> path,
                           const RenderRunOptions& o) {
  RenderRunResult r;
  std::vector<double> ms;
  // Every memory_every frames, outside the timed spans: hand freed heap pages
  // back (see release_free_heap) and sample RSS.
  r.memory.samples.emplace_back(0, resident_mb());
  fly(
      renderer, path, o.read,
      [&](int local, const Frame& f) {
        if (o.on_frame) o.on_frame(o.first_frame + local, f);
      },
      [&](const FrameStats& s) {
        r.frames.push_back({o.first_frame + s.frame, s.cls, s.ms, s.gpu_ms, s.triangles});
        ms.push_back(s.ms);
        const int done = int(r.frames.size());
        if (done % o.memory_every == 0) {
          if (o.heap_trim) r.memory.trim_ms += release_free_heap();
          r.memory.samples.emplace_back(done, resident_mb());
        }
      },
      o.progress);
  r.median_ms = median(ms);
  r.peak_rss_mb = peak_resident_mb();
  return r;
}

}  // namespace terrasprite
