// SPDX-License-Identifier: MIT
// bench stream's in-memory peer (see bench_stream_peer.h): the child process
// and the parent's pipe protocol.
#include "bench_stream_peer.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <optional>

#include "process_memory.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/stream/streaming_tiles.h"
#include "terrasprite/voxel/voxel_renderer.h"

extern char** environ;

namespace terrasprite::cli {
namespace {

// ---- The in-memory half, in its own process (so its memory is not the
// streamed run's), run in lockstep with the streamed frames: the parent
// draws frame i, then asks the child for frame i and waits for it. So each
// pair is timed seconds apart under the same machine load, and the ratio and
// the stall count compare like with like. ----
constexpr int kChildIn = 3, kChildOut = 4;  // the child's ends of the two pipes

bool write_all(int fd, const void* data, std::size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t k = ::write(fd, p, n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k;
    n -= std::size_t(k);
  }
  return true;
}

bool read_all(int fd, void* data, std::size_t n) {
  char* p = static_cast<char*>(data);
  while (n > 0) {
    const ssize_t k = ::read(fd, p, n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k;
    n -= std::size_t(k);
  }
  return true;
}

// The child's cameras: frame i once the parent has asked for it; ends when
// the parent closes the pipe.
class LockstepSource final : public CameraSource {
 public:
  explicit LockstepSource(const std::vector<Camera>& path) : path_(path) {}
  std::optional<Camera> camera(int frame) override {
    while (asked_ < frame) {
      std::int32_t i = 0;
      if (!read_all(kChildIn, &i, sizeof i) || i < 0 || i >= int(path_.size())) return std::nullopt;
      asked_ = i;
    }
    if (asked_ != frame) return std::nullopt;
    return path_[std::size_t(frame)];
  }
  int frames() const override { return int(path_.size()); }

 private:
  const std::vector<Camera>& path_;
  int asked_ = -1;
};

}  // namespace

std::uint64_t image_hash(const Image& im) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint8_t b : im.rgba) h = (h ^ b) * 1099511628211ull;
  return h;
}

void run_in_memory_child(const BenchStreamOpts& o, const TileSetInfo& set, int w, int h,
                         const std::vector<Camera>& path) {
  ResidentTiles tiles(set);
  VoxelOptions vo;
  vo.threads = o.threads;
  VoxelRenderer r(tiles, w, h, vo);
  // One unshown draw before the run, as the streamed side's first-view draw:
  // frame 0 is warm on both sides.
  if (o.first_view_ms > 0 && !path.empty()) r.draw(path.front());
  ChildReply ready;
  if (!write_all(kChildOut, &ready, sizeof ready)) return;
  LockstepSource cameras(path);
  Experiment ex;
  int frame = 0;
  ex.add({.renderer = &r, .name = "in_memory", .annotate = [&](const Frame& f, FrameResult& fr) {
            const ChildReply reply{frame++, fr.ms, image_hash(f.color), peak_resident_mb()};
            if (!write_all(kChildOut, &reply, sizeof reply)) std::exit(0);  // the parent is gone
          }});
  ExperimentOptions eo;
  eo.warmup_draws = 0;
  ex.run(cameras, eo);
}

InMemoryPeer::InMemoryPeer(const BenchStreamOpts& o) {
  int to_child[2], from_child[2];
  if (pipe2(to_child, O_CLOEXEC) != 0) return;
  if (pipe2(from_child, O_CLOEXEC) != 0) {
    ::close(to_child[0]);
    ::close(to_child[1]);
    return;
  }
  std::vector<std::string> args = {"/proc/self/exe",
                                   "bench",
                                   "stream",
                                   o.cog.empty() ? "--tiles" : "--cog",
                                   o.cog.empty() ? o.tiles : o.cog,
                                   "--size",
                                   o.size,
                                   "--path",
                                   o.path,
                                   "--frames",
                                   std::to_string(o.frames),
                                   "--threads",
                                   std::to_string(o.threads),
                                   "--first-view-ms",
                                   std::to_string(o.first_view_ms),
                                   "--in-memory-child"};
  if (!o.texture.empty()) args.insert(args.end(), {"--texture", o.texture});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, to_child[0], kChildIn);  // dup2 clears O_CLOEXEC
  posix_spawn_file_actions_adddup2(&fa, from_child[1], kChildOut);
  const bool spawned =
      posix_spawn(&pid_, "/proc/self/exe", &fa, nullptr, argv.data(), environ) == 0;
  posix_spawn_file_actions_destroy(&fa);
  ::close(to_child[0]);
  ::close(from_child[1]);
  to_ = to_child[1];
  from_ = from_child[0];
  ChildReply ready;
  ok_ = spawned && read_all(from_, &ready, sizeof ready) && ready.frame == -1;
  if (!spawned) pid_ = 0;
  if (!ok_) fail();
}

InMemoryPeer::~InMemoryPeer() {
  if (to_ >= 0) ::close(to_);
  if (from_ >= 0) ::close(from_);
  if (pid_ > 0) {
    int status = 0;
    waitpid(pid_, &status, 0);
  }
}

bool InMemoryPeer::frame(int i, ChildReply& reply) {
  if (!ok_) return false;
  const std::int32_t k = i;
  if (write_all(to_, &k, sizeof k) && read_all(from_, &reply, sizeof reply) && reply.frame == i) {
    peak_rss_mb_ = std::max(peak_rss_mb_, reply.peak_rss_mb);
    return true;
  }
  fail();
  return false;
}

void InMemoryPeer::fail() {
  if (ok_ || !warned_)
    fmt::print(stderr, "warning: the in-memory run failed; reporting the streamed run alone\n");
  ok_ = false;
  warned_ = true;
}

}  // namespace terrasprite::cli
