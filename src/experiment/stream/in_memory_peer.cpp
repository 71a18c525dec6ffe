// SPDX-License-Identifier: MIT
// The streaming study's in-memory peer (see in_memory_peer.h): the child
// process and the parent's pipe protocol.
#include "in_memory_peer.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <optional>

#include "stream/tile_file.h"
#include "terrasprite/common/error.h"
#include "terrasprite/common/process_memory.h"
#include "terrasprite/experiment/experiment.h"
#include "terrasprite/stream/streaming_tiles.h"
#include "terrasprite/voxel/voxel_renderer.h"

extern char** environ;

namespace terrasprite::stream_bench {
namespace {

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

Heightfield path_proxy(const TileSetInfo& set) {
  int L = 0;
  while (L < set.grid.coarsest_level && std::max(set.level_w(L), set.level_h(L)) > 1025) ++L;
  Heightfield h;
  std::string error;
  if (!TileFile(set).read_level_heights(L, h.heights, error))
    throw InputError(fmt::format("{}: {}", set.dir, error));
  h.width = set.level_w(L);
  h.height = set.level_h(L);
  h.spacing_x = set.grid.spacing_x * (set.grid.width - 1) / double(h.width - 1);
  h.spacing_y = set.grid.spacing_y * (set.grid.height - 1) / double(h.height - 1);
  h.name = set.dir;
  return h;
}

void run_in_memory_child(const TileSetInfo& set, int w, int h, int threads, bool first_view,
                         const std::vector<Camera>& path) {
  ResidentTiles tiles(set);
  VoxelOptions vo;
  vo.threads = threads;
  VoxelRenderer r(tiles, w, h, vo);
  // One unshown draw before the run, as the streamed side's first-view draw:
  // frame 0 is warm on both sides.
  if (first_view && !path.empty()) r.draw(path.front());
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

InMemoryPeer::InMemoryPeer(const std::vector<std::string>& command) {
  int to_child[2], from_child[2];
  if (pipe2(to_child, O_CLOEXEC) != 0) return;
  if (pipe2(from_child, O_CLOEXEC) != 0) {
    ::close(to_child[0]);
    ::close(to_child[1]);
    return;
  }
  std::vector<std::string> args = command;
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, to_child[0], kChildIn);  // dup2 clears O_CLOEXEC
  posix_spawn_file_actions_adddup2(&fa, from_child[1], kChildOut);
  const bool spawned =
      posix_spawn(&pid_, args[0].c_str(), &fa, nullptr, argv.data(), environ) == 0;
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

}  // namespace terrasprite::stream_bench
