// SPDX-License-Identifier: MIT
// The streaming study's in-memory peer: the same flythrough with the whole
// terrain resident, run in a child process (so its memory is not the
// streamed run's) in lockstep with the streamed frames: the parent draws
// frame i, then asks the child for frame i and waits for it, so each pair is
// timed seconds apart under the same machine load.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/common/image.h"
#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite::stream_bench {

/// One frame's answer from the in-memory child.
struct ChildReply {
  std::int32_t frame = -1;  ///< -1: ready (its tiles are loaded)
  double ms = 0;
  std::uint64_t hash = 0;
  double peak_rss_mb = 0;
};

/// FNV-1a over the colour bytes: frames compared across processes by hash.
std::uint64_t image_hash(const Image& im);

/// The path is planned over a coarse level of the tiled terrain (at most 1025
/// samples a side), read once: the full-resolution grid never loads. Throws
/// InputError naming the set when the level cannot be read.
Heightfield path_proxy(const TileSetInfo& set);

/// The child's side: loads `set` into memory, answers "ready", then draws
/// frame i of `path` each time the parent asks (frame numbers on fd 3,
/// ChildReply on fd 4) until the parent closes the pipe. `threads`: the ray
/// caster's; `first_view`: one unshown draw of frame 0 first, as the
/// streamed side's first-view draw.
void run_in_memory_child(const TileSetInfo& set, int w, int h, int threads, bool first_view,
                         const std::vector<Camera>& path);

/// The parent's side: the child process and its two pipes.
class InMemoryPeer {
 public:
  /// Starts `command` (argv[0]: the executable) as the child and waits until
  /// its terrain is resident; ok() is false (with a one-line warning) when it
  /// could not start.
  explicit InMemoryPeer(const std::vector<std::string>& command);
  ~InMemoryPeer();  ///< closes the pipes (the child ends) and reaps the child
  InMemoryPeer(const InMemoryPeer&) = delete;
  InMemoryPeer& operator=(const InMemoryPeer&) = delete;
  bool ok() const { return ok_; }
  /// Frame i in memory: its ms and image hash; false (once warned) if the child is gone.
  bool frame(int i, ChildReply& reply);
  double peak_rss_mb() const { return peak_rss_mb_; }

 private:
  void fail();
  pid_t pid_ = 0;
  int to_ = -1, from_ = -1;
  bool ok_ = false, warned_ = false;
  double peak_rss_mb_ = 0;
};

}  // namespace terrasprite::stream_bench
