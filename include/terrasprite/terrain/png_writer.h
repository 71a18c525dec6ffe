// SPDX-License-Identifier: MIT
// PNG files written on a worker thread, so encoding a frame sequence (stb's
// deflate) overlaps the caller's rendering instead of adding to it.
#pragma once
#include <memory>
#include <string>

#include "terrasprite/common/image.h"

namespace terrasprite {

/// Writes each pushed image with save_png() on one worker thread, in push
/// order. The first error (an unwritable file: InputError naming it) is
/// rethrown from the next push() or from finish(); later images are dropped.
/// The destructor without finish() waits for the queued images and drops
/// any error.
class PngWriter {
 public:
  /// At most `queue_images` (>= 1) images wait; push() blocks beyond that.
  explicit PngWriter(int queue_images = 4);
  ~PngWriter();
  PngWriter(const PngWriter&) = delete;
  PngWriter& operator=(const PngWriter&) = delete;

  /// Queues `image` (RGBA8, moved in) for `path`.
  void push(Image image, std::string path);
  /// Waits until every queued image is written; rethrows the first error.
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace terrasprite
