// SPDX-License-Identifier: MIT
#include "gl/frame_timer.h"

namespace terrasprite::gl {

void FrameTimer::begin() {
  start_ = std::chrono::steady_clock::now();
  glBeginQuery(GL_TIME_ELAPSED, query_.id());
}

FrameTime FrameTimer::end() {
  glEndQuery(GL_TIME_ELAPSED);
  glFinish();
  FrameTime t;
  t.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  GLuint64 ns = 0;
  glGetQueryObjectui64v(query_.id(), GL_QUERY_RESULT, &ns);
  // GPU time inside the span cannot exceed its wall time; llvmpipe reports
  // nonsense (minutes) for the first query of a process, so such a value is
  // "no result" (-1), which every statistic skips.
  const double gpu = double(ns) / 1e6;
  t.gpu_ms = gpu <= t.ms * 1.05 + 0.1 ? gpu : -1.0;
  return t;
}

}  // namespace terrasprite::gl
