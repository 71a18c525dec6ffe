// SPDX-License-Identifier: MIT
// The one GL frame timer: wall clock to glFinish plus a GL timer query.
#pragma once
#include <chrono>

#include "gl/gl_objects.h"

namespace terrasprite::gl {

struct FrameTime {
  double ms = 0.0;       ///< wall clock from begin() to the drained pipeline
  double gpu_ms = -1.0;  ///< GL_TIME_ELAPSED, or -1 when the driver gave no usable result
};

/// begin() starts the wall clock and a GL_TIME_ELAPSED query; end() ends the
/// query, drains the pipeline (glFinish) and returns both times. Spans must
/// not nest (GL allows one time-elapsed query at a time). A current context.
class FrameTimer {
 public:
  void begin();
  FrameTime end();

 private:
  Query query_{GL_TIME_ELAPSED};
  std::chrono::steady_clock::time_point start_;
};

}  // namespace terrasprite::gl
