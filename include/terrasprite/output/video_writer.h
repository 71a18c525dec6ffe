// SPDX-License-Identifier: MIT
// H.264 video of a flythrough through an ffmpeg child process (no libav
// linking): raw RGBA frames go down a pipe from a writer thread, so encoding
// overlaps rendering.
#pragma once
#include <memory>
#include <string>

#include "terrasprite/common/image.h"

namespace terrasprite {

struct VideoOptions {
  double fps = 30.0;                ///< frames per second of the stream, > 0
  int crf = 18;                     ///< x264 constant rate factor, 0..51 (lower: better)
  std::string preset = "veryfast";  ///< x264 preset (ultrafast .. placebo)
  int queue_frames = 4;             ///< frames buffered between caller and writer thread
  /// An encoder that reads nothing for this long has failed (it is killed).
  double stall_seconds = 60.0;
  /// The ffmpeg executable; empty: $TERRASPRITE_FFMPEG, else "ffmpeg" on PATH.
  std::string ffmpeg;
};

/// Throws InputError naming `option` for an fps, crf or preset ffmpeg would refuse.
void validate_video_options(const VideoOptions& o, const std::string& option = "--video");

/// Writes an MP4 (H.264, yuv420p, +faststart) of `width` x `height` frames.
/// The stream goes to a fresh temporary file beside `file` (`.NAME.tmp-XXXXXX`,
/// never a name of the user's) and is renamed to `file` by finish(), so an
/// interrupted or failed run never leaves a file that looks complete (the
/// destructor without finish() kills ffmpeg and removes the temporary file).
/// The MP4's comment is generator_name(), so a rerun may replace it.
/// H.264 in 4:2:0 needs even sizes: an odd width or height is padded by one
/// pixel that repeats the last column or row (padded() says so).
/// Errors (ffmpeg missing, encoder failure, disk full) throw InputError with
/// one line naming `file`; from push() as soon as the writer thread sees them,
/// at the latest from finish().
class VideoWriter {
 public:
  VideoWriter(std::string file, int width, int height, const VideoOptions& options = {});
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Queues one frame (RGBA8, width x height as constructed, rows top to
  /// bottom); blocks while the queue is full. The image is copied.
  void push(const Image& frame);
  /// Closes the stream, waits for ffmpeg and moves the file into place.
  void finish();

  int frames() const;         ///< frames pushed so far
  bool padded() const;        ///< an odd size was padded to even
  int encoded_width() const;  ///< width in the stream (even)
  int encoded_height() const;
  const std::string& file() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace terrasprite
