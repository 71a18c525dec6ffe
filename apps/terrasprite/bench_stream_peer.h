// SPDX-License-Identifier: MIT
// bench stream's options, and its in-memory peer: the same flythrough with the
// whole terrain resident, run in a child process (so its memory is not the
// streamed run's) in lockstep with the streamed frames.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/common/image.h"
#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite::cli {

struct BenchStreamOpts {
  std::string tiles;
  std::string cog, texture;
  int cache_mb = 256;
  int io_threads = 2;
  std::string size = "1920x1080";
  std::string path = "low-fast";
  int frames = 300;
  int threads = 0;
  std::string in_memory = "auto";
  int first_view_ms = 600;  // longest wait for the first view's tiles before frame 0
  bool child = false;  // hidden: be the in-memory peer (frame numbers on fd 3, answers on fd 4)
  std::string json;
  std::string out;
};

/// One frame's answer from the in-memory child.
struct ChildReply {
  std::int32_t frame = -1;  ///< -1: ready (its tiles are loaded)
  double ms = 0;
  std::uint64_t hash = 0;
  double peak_rss_mb = 0;
};

/// FNV-1a over the colour bytes: frames compared across processes by hash.
std::uint64_t image_hash(const Image& im);

/// The child's whole life (`--in-memory-child`): loads `set` into memory,
/// answers "ready", then draws frame i of `path` each time the parent asks
/// (frame numbers on fd 3, ChildReply on fd 4) until the parent closes the pipe.
void run_in_memory_child(const BenchStreamOpts& o, const TileSetInfo& set, int w, int h,
                         const std::vector<Camera>& path);

/// The parent's side: the child process and its two pipes.
class InMemoryPeer {
 public:
  /// Starts this program again as the child and waits until its terrain is
  /// resident; ok() is false (with a one-line warning) when it could not start.
  explicit InMemoryPeer(const BenchStreamOpts& o);
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

}  // namespace terrasprite::cli
