// SPDX-License-Identifier: MIT
// The streaming tile cache (Cohen-Or et al.'s out-of-core terrain): a table of
// resident tiles that only update() changes, loader threads that read queued
// tiles through their own GDAL handles, and a byte budget held by evicting the
// least recently wanted tiles, farthest first.
#include "terrasprite/stream/streaming_tiles.h"

#include <fmt/format.h>
#include <gdal.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <thread>
#include <utility>

#include "stream/footprint.h"
#include "stream/tile_file.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace {

enum class State : std::uint8_t { kEmpty, kQueued, kResident, kFailed };

// Lookups counted per thread shard, so the renderer's threads do not share a line.
struct alignas(64) Shard {
  std::atomic<long long> lookups{0}, misses{0};
};
constexpr int kShards = 16;
int shard_index() {
  static std::atomic<int> next{0};
  thread_local const int i = next.fetch_add(1, std::memory_order_relaxed) % kShards;
  return i;
}

// A repeatable "random" draw in [0, 1) per tile, for fault injection.
double tile_hash01(int level, int tx, int ty) {
  std::uint64_t h = std::uint64_t(level) * 0x9E3779B97F4A7C15ull ^
                    std::uint64_t(tx) * 0xC2B2AE3D27D4EB4Full ^
                    std::uint64_t(ty) * 0x165667B19E3779F9ull;
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  return double(h >> 11) / double(1ull << 53);
}

struct Job {
  int level, tx, ty;
  std::size_t reserved;
};

struct Done {
  Job job;
  std::unique_ptr<TileData> data;  // null: failed
  bool injected = false;
  std::string error;
};

// a += b, field by field (a base and its fine levels' frame figures).
void add_stats(StreamFrameStats& a, const StreamFrameStats& b) {
  a.lookups += b.lookups;
  a.misses += b.misses;
  a.degraded_samples = a.misses;
  a.requested += b.requested;
  a.loaded += b.loaded;
  a.evicted += b.evicted;
  a.failed += b.failed;
  a.bytes_read += b.bytes_read;
  a.resident_bytes += b.resident_bytes;
  a.resident_tiles += b.resident_tiles;
}

}  // namespace

struct StreamingTiles::Impl {
  TileSetInfo set;
  StreamOptions o;
  // Fine levels (insets): their own cache over the window set; the base's
  // levels are the renderer's levels k.. (see combined_grid).
  int k = 0;
  TerrainGrid cgrid;
  std::unique_ptr<StreamingTiles> fine;
  double shift_x = 0, shift_y = 0;  // the window set's frame -> world
  int pin_from = 0;  // levels pin_from.. are pinned
  std::vector<std::vector<std::unique_ptr<TileData>>> table;
  std::vector<std::vector<State>> state;
  std::vector<std::vector<int>> last_wanted;
  // The frame a resident tile was last read in: a tile the march reads but the
  // footprint does not want (it is wide of it) is not evicted ahead of the
  // older ones, which made 32769² reload such tiles over and over.
  std::vector<std::unique_ptr<std::atomic<int>[]>> last_read;
  std::vector<std::unique_ptr<std::atomic<std::uint8_t>[]>> demand;
  mutable Shard shards[kShards];
  std::size_t resident = 0, pinned = 0;
  int frame = 0;
  int failed = 0;
  // Since the last update(): tiles installed, their bytes, failures.
  int loaded_since = 0, failed_since = 0;
  long long bytes_since = 0;
  glm::dvec3 last_pos{0.0};
  bool have_last = false;

  // Loader side.
  std::mutex m;
  std::condition_variable cv, idle_cv;
  std::deque<Job> queue;
  std::vector<Done> done;
  std::size_t inflight_bytes = 0;  // queued + loading reservations
  int loading = 0;
  std::atomic<int> injected{0};
  std::vector<std::jthread> threads;

  std::size_t idx(int L, int tx, int ty) const {
    return std::size_t(ty) * std::size_t(set.tiles_x[std::size_t(L)]) + std::size_t(tx);
  }
  void load_loop(std::stop_token stop, std::unique_ptr<TileFile> file);
  bool read_one(TileFile& file, const Job& j, Done& d);
  int install();
  void evict(int L, std::size_t i);
  void plan(const Camera& cam, StreamFrameStats& st);
  void load_pinned(std::vector<std::unique_ptr<TileFile>>& files);
};

// Reads the pinned levels, one share of the tiles per loader handle in
// parallel; throws InputError on the first failure (a broken file at start).
void StreamingTiles::Impl::load_pinned(std::vector<std::unique_ptr<TileFile>>& files) {
  std::vector<Job> jobs;
  for (int L = pin_from; L < int(table.size()); ++L)
    for (int ty = 0; ty < set.tiles_y[std::size_t(L)]; ++ty)
      for (int tx = 0; tx < set.tiles_x[std::size_t(L)]; ++tx) jobs.push_back({L, tx, ty, 0});
  std::vector<std::unique_ptr<TileData>> data(jobs.size());
  std::vector<std::string> errors(files.size());
  {
    std::vector<std::jthread> workers;
    for (std::size_t t = 0; t < files.size(); ++t)
      workers.emplace_back([&, t] {
        for (std::size_t k = t; k < jobs.size() && errors[t].empty(); k += files.size()) {
          data[k] = std::make_unique<TileData>();
          if (!files[t]->read(jobs[k].level, jobs[k].tx, jobs[k].ty, *data[k], errors[t]))
            data[k].reset();
        }
      });
  }
  for (const std::string& e : errors)
    if (!e.empty()) throw InputError(fmt::format("{}: {}", set.dir, e));
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const std::size_t i = idx(jobs[k].level, jobs[k].tx, jobs[k].ty);
    resident += data[k]->bytes();
    table[std::size_t(jobs[k].level)][i] = std::move(data[k]);
    state[std::size_t(jobs[k].level)][i] = State::kResident;
  }
  pinned = resident;
}

bool StreamingTiles::Impl::read_one(TileFile& file, const Job& j, Done& d) {
  if (o.before_read) o.before_read(j.level, j.tx, j.ty);
  if ((o.fail_read && o.fail_read(j.level, j.tx, j.ty)) ||
      (o.fault_rate > 0 && tile_hash01(j.level, j.tx, j.ty) < o.fault_rate)) {
    d.injected = true;
    d.error = "injected read fault";
    return false;
  }
  auto data = std::make_unique<TileData>();
  if (!file.read(j.level, j.tx, j.ty, *data, d.error)) return false;
  d.data = std::move(data);
  return true;
}

void StreamingTiles::Impl::load_loop(std::stop_token stop, std::unique_ptr<TileFile> file) {
  // Below the renderer's threads: on a machine with few cores, decoding ahead
  // of need should not slow the frame being drawn.
  setpriority(PRIO_PROCESS, pid_t(syscall(SYS_gettid)), 10);
  for (;;) {
    Job j;
    {
      std::unique_lock lk(m);
      cv.wait(lk, [&] { return stop.stop_requested() || !queue.empty(); });
      if (stop.stop_requested()) return;
      j = queue.front();
      queue.pop_front();
      ++loading;
    }
    Done d{j, nullptr, false, {}};
    read_one(*file, j, d);
    {
      std::lock_guard lk(m);
      done.push_back(std::move(d));
      --loading;
    }
    idle_cv.notify_all();
  }
}

// Moves finished reads into the table. Returns the tiles installed.
int StreamingTiles::Impl::install() {
  std::vector<Done> finished;
  {
    std::lock_guard lk(m);
    finished.swap(done);
    for (const Done& d : finished) inflight_bytes -= d.job.reserved;
  }
  int n = 0;
  for (Done& d : finished) {
    const Job& j = d.job;
    const std::size_t i = idx(j.level, j.tx, j.ty);
    if (!d.data) {
      state[std::size_t(j.level)][i] = State::kFailed;
      ++failed;
      ++failed_since;
      if (d.injected) injected.fetch_add(1, std::memory_order_relaxed);
      fmt::print(stderr,
                 "terrasprite: warning: {}: tile ({}, {}) of level {} failed ({}); served from a "
                 "coarser level from now on\n",
                 set.dir, j.tx, j.ty, j.level, d.error);
      continue;
    }
    resident += d.data->bytes();
    bytes_since += (long long)d.data->bytes();
    ++loaded_since;
    table[std::size_t(j.level)][i] = std::move(d.data);
    state[std::size_t(j.level)][i] = State::kResident;
    ++n;
  }
  return n;
}

void StreamingTiles::Impl::evict(int L, std::size_t i) {
  resident -= table[std::size_t(L)][i]->bytes();
  table[std::size_t(L)][i].reset();
  state[std::size_t(L)][i] = State::kEmpty;
}

// Queues the wanted tiles in priority order while the budget allows, evicting
// unwanted tiles (oldest, then farthest) to make room.
void StreamingTiles::Impl::plan(const Camera& cam, StreamFrameStats& st) {
  std::vector<TileKey> want;
  for (int L = 0; L < pin_from; ++L) {  // last frame's misses come first, coarsest first
    const std::size_t n = state[std::size_t(L)].size();
    for (std::size_t i = 0; i < n; ++i)
      if (demand[std::size_t(L)][i].exchange(0, std::memory_order_relaxed))
        want.push_back({L, int(i % std::size_t(set.tiles_x[std::size_t(L)])),
                        int(i / std::size_t(set.tiles_x[std::size_t(L)])), -1.0 - L});
  }
  FootprintOptions fo{o.margin, o.lookahead_frames, o.pixel_voxel_ratio, o.image_height, pin_from};
  const glm::dvec3 motion = have_last ? cam.position - last_pos : glm::dvec3(0.0);
  footprint(set, cam, motion, fo, want);
  if (!set.present.empty())  // a fine window set: tiles without inset data are never read
    std::erase_if(want, [&](const TileKey& t) { return !set.tile_present(t.level, t.tx, t.ty); });
  std::stable_sort(want.begin(), want.end(),
                   [](const TileKey& a, const TileKey& b) { return a.priority < b.priority; });
  for (const TileKey& k : want) last_wanted[std::size_t(k.level)][idx(k.level, k.tx, k.ty)] = frame;

  // Un-queue reads not started: they are planned afresh below.
  std::unique_lock lk(m);
  for (const Job& j : queue) {
    state[std::size_t(j.level)][idx(j.level, j.tx, j.ty)] = State::kEmpty;
    inflight_bytes -= j.reserved;
  }
  queue.clear();
  struct Victim {
    int L;
    std::size_t i;
    double score;
  };
  // Tiles the last frame read are evicted only for tiles a frame missed, never
  // to prefetch: a tile the march reads wide of the footprint would otherwise
  // be evicted for prefetch and missed again.
  std::vector<Victim> idle, in_use;
  for (int L = 0; L < pin_from; ++L)
    for (std::size_t i = 0; i < state[std::size_t(L)].size(); ++i) {
      if (state[std::size_t(L)][i] != State::kResident) continue;
      const int read = last_read[std::size_t(L)][i].load(std::memory_order_relaxed);
      const int recent = std::max(last_wanted[std::size_t(L)][i], read);
      if (recent >= frame) continue;
      const int nx = set.tiles_x[std::size_t(L)];
      const double reach = level_reach(set, cam, fo, L);
      const double d =
          tile_distance(set, L, int(i % nx), int(i / nx), cam.position.x, cam.position.y);
      (read == frame - 1 ? in_use : idle).push_back({L, i, double(frame - recent) + d / reach});
    }
  auto by_score = [](const Victim& a, const Victim& b) { return a.score < b.score; };
  std::sort(idle.begin(), idle.end(), by_score);
  std::sort(in_use.begin(), in_use.end(), by_score);
  for (const TileKey& k : want) {
    const std::size_t i = idx(k.level, k.tx, k.ty);
    if (state[std::size_t(k.level)][i] != State::kEmpty) continue;
    const std::size_t need = tile_bytes(set, k.level, k.tx, k.ty);
    const bool missed = k.priority < 0;  // a frame read coarser for want of it
    while (resident + inflight_bytes + need > o.cache_bytes) {
      std::vector<Victim>& from = !idle.empty() ? idle : in_use;
      if (from.empty() || (&from == &in_use && !missed)) break;
      evict(from.back().L, from.back().i);
      from.pop_back();
      ++st.evicted;
    }
    if (resident + inflight_bytes + need > o.cache_bytes) break;
    queue.push_back({k.level, k.tx, k.ty, need});
    inflight_bytes += need;
    state[std::size_t(k.level)][i] = State::kQueued;
    ++st.requested;
  }
  lk.unlock();
  cv.notify_all();
}

StreamingTiles::StreamingTiles(const TileSetInfo& set, StreamOptions options)
    : p_(std::make_unique<Impl>()) {
  Impl& p = *p_;
  p.set = set;
  p.o = std::move(options);
  if (const char* env = std::getenv("TERRASPRITE_STREAM_FAULTS")) p.o.fault_rate = std::atof(env);
  if (p.o.io_threads < 1 || p.o.io_threads > 64)
    throw InputError(fmt::format("io_threads {}: must be 1..64", p.o.io_threads));
  if (!(p.o.fault_rate >= 0 && p.o.fault_rate <= 1))
    throw InputError(
        fmt::format("TERRASPRITE_STREAM_FAULTS {}: must be a share within 0..1", p.o.fault_rate));
  GDALSetCacheMax64(GIntBig(p.o.gdal_cache_bytes));
  p.cgrid = combined_grid(p.set);
  if (p.set.fine && p.set.fine_set) {
    if (!(p.o.fine_share > 0 && p.o.fine_share < 1))
      throw InputError(fmt::format("fine_share {}: must be within (0, 1)", p.o.fine_share));
    p.k = p.set.fine->levels;
    fine_world_shift(p.set, p.shift_x, p.shift_y);
    StreamOptions fo = p.o;
    fo.cache_bytes = std::size_t(double(p.o.cache_bytes) * p.o.fine_share);
    p.o.cache_bytes -= fo.cache_bytes;
    const TileSetInfo& f = *p.set.fine_set;
    auto global = [&f](int level, int& tx, int& ty) {
      tx += (f.origin_x >> level) >> f.grid.tile_log2;
      ty += (f.origin_y >> level) >> f.grid.tile_log2;
    };
    if (p.o.before_read)
      fo.before_read = [hook = p.o.before_read, global](int level, int tx, int ty) {
        global(level, tx, ty);
        hook(level, tx, ty);
      };
    if (p.o.fail_read)
      fo.fail_read = [hook = p.o.fail_read, global](int level, int tx, int ty) {
        global(level, tx, ty);
        return hook(level, tx, ty);
      };
    const int k = p.k;  // the base's hooks see the renderer's levels
    if (p.o.before_read)
      p.o.before_read = [hook = p.o.before_read, k](int level, int tx, int ty) {
        hook(level + k, tx, ty);
      };
    if (p.o.fail_read)
      p.o.fail_read = [hook = p.o.fail_read, k](int level, int tx, int ty) {
        return hook(level + k, tx, ty);
      };
    p.fine = std::make_unique<StreamingTiles>(f, std::move(fo));
  }
  const TerrainGrid& g = p.set.grid;
  const int nl = g.bound_levels;
  p.table.resize(std::size_t(nl));
  p.state.resize(std::size_t(nl));
  p.last_wanted.resize(std::size_t(nl));
  std::vector<std::size_t> level_bytes(std::size_t(nl), 0);
  for (int L = 0; L < nl; ++L) {
    const std::size_t n =
        std::size_t(p.set.tiles_x[std::size_t(L)]) * p.set.tiles_y[std::size_t(L)];
    p.table[std::size_t(L)].resize(n);
    p.state[std::size_t(L)].assign(n, State::kEmpty);
    p.last_wanted[std::size_t(L)].assign(n, -1);
    p.demand.emplace_back(new std::atomic<std::uint8_t>[n]);
    for (std::size_t i = 0; i < n; ++i) p.demand.back()[i].store(0);
    p.last_read.emplace_back(new std::atomic<int>[n]);
    for (std::size_t i = 0; i < n; ++i) p.last_read.back()[i].store(-1);
    for (int ty = 0; ty < p.set.tiles_y[std::size_t(L)]; ++ty)
      for (int tx = 0; tx < p.set.tiles_x[std::size_t(L)]; ++tx)
        level_bytes[std::size_t(L)] += tile_bytes(p.set, L, tx, ty);
  }
  // Pin from the coarsest down while the share allows (the coarsest sample level always).
  p.pin_from = g.coarsest_level;
  std::size_t pinned = 0;
  for (int L = nl - 1; L >= g.coarsest_level; --L) pinned += level_bytes[std::size_t(L)];
  while (p.pin_from > 0 && pinned + level_bytes[std::size_t(p.pin_from - 1)] <=
                               std::size_t(p.o.pinned_share * double(p.o.cache_bytes))) {
    --p.pin_from;
    pinned += level_bytes[std::size_t(p.pin_from)];
  }
  if (pinned > p.o.cache_bytes)
    throw InputError(fmt::format("cache_mb {:.1f}: below the {:.1f} MB the coarsest levels need",
                                 double(p.o.cache_bytes) / (1 << 20), double(pinned) / (1 << 20)));
  std::vector<std::unique_ptr<TileFile>> files;
  for (int t = 0; t < p.o.io_threads; ++t) files.push_back(std::make_unique<TileFile>(p.set));
  p.load_pinned(files);
  for (auto& f : files)
    p.threads.emplace_back([&p, file = std::move(f)](std::stop_token st) mutable {
      p.load_loop(st, std::move(file));
    });
}

StreamingTiles::~StreamingTiles() {
  {
    std::lock_guard lk(p_->m);  // a loader between its check and its wait must not miss this
    for (auto& t : p_->threads) t.request_stop();
  }
  p_->cv.notify_all();
  p_->threads.clear();  // joins
}

const TerrainGrid& StreamingTiles::grid() const {
  return p_->cgrid;
}

const TileBlock* StreamingTiles::tile(int level, int tx, int ty) const {
  const Impl& p = *p_;
  if (p.k) {
    if (level < p.k)
      return fine_window_tile(*p.set.fine_set, level, tx, ty) ? p.fine->tile(level, tx, ty)
                                                              : nullptr;
    level -= p.k;
  }
  if (level < 0 || level >= int(p.table.size())) return nullptr;
  const int nx = p.set.tiles_x[std::size_t(level)], ny = p.set.tiles_y[std::size_t(level)];
  if (tx < 0 || ty < 0 || tx >= nx || ty >= ny) return nullptr;
  const std::size_t i = p.idx(level, tx, ty);
  Shard& s = p.shards[shard_index()];
  s.lookups.fetch_add(1, std::memory_order_relaxed);
  const TileData* d = p.table[std::size_t(level)][i].get();
  if (d) [[likely]] {
    auto& read = p.last_read[std::size_t(level)][i];  // once per tile crossing, not per read
    if (read.load(std::memory_order_relaxed) != p.frame)
      read.store(p.frame, std::memory_order_relaxed);
    return &d->block;
  }
  s.misses.fetch_add(1, std::memory_order_relaxed);
  auto& flag = p.demand[std::size_t(level)][i];
  if (!flag.load(std::memory_order_relaxed))
    flag.store(1, std::memory_order_relaxed);  // no line ping-pong
  return nullptr;
}

void StreamingTiles::collect_reads(StreamFrameStats& st) const {
  for (Shard& s : p_->shards) {
    st.lookups += s.lookups.exchange(0, std::memory_order_relaxed);
    st.misses += s.misses.exchange(0, std::memory_order_relaxed);
  }
  st.degraded_samples = st.misses;
  if (p_->fine) {
    StreamFrameStats f;
    p_->fine->collect_reads(f);
    add_stats(st, f);
  }
}

StreamFrameStats StreamingTiles::update(const Camera& camera) {
  Impl& p = *p_;
  StreamFrameStats st;
  collect_reads(st);
  p.install();
  st.loaded = std::exchange(p.loaded_since, 0);
  st.bytes_read = std::exchange(p.bytes_since, 0);
  st.failed = std::exchange(p.failed_since, 0);
  ++p.frame;
  p.plan(camera, st);
  p.last_pos = camera.position;
  p.have_last = true;
  {
    std::lock_guard lk(p.m);
    st.resident_bytes = p.resident + p.inflight_bytes;
  }
  for (const auto& lv : p.state)
    st.resident_tiles += int(std::count(lv.begin(), lv.end(), State::kResident));
  if (p.fine) {  // the window set in its own frame
    Camera c = camera;
    c.position.x -= p.shift_x;
    c.position.y -= p.shift_y;
    add_stats(st, p.fine->update(c));
  }
  return st;
}

int StreamingTiles::settle() {
  Impl& p = *p_;
  {
    std::unique_lock lk(p.m);
    p.idle_cv.wait(lk, [&] { return p.queue.empty() && p.loading == 0; });
  }
  return p.install() + (p.fine ? p.fine->settle() : 0);
}

StreamingTiles::FirstView StreamingTiles::wait_for_first_view(
    const Camera& camera, std::chrono::steady_clock::time_point deadline) {
  // The tiles the unshown draw missed, in this set and its fine one.
  struct Wanted {
    Impl* p;
    int level;
    std::size_t i;
  };
  std::vector<Wanted> wanted;
  for (StreamingTiles* t = this; t; t = t->p_->fine.get()) {
    Impl& p = *t->p_;
    for (int L = 0; L < p.pin_from; ++L)
      for (std::size_t i = 0; i < p.state[std::size_t(L)].size(); ++i)
        if (p.demand[std::size_t(L)][i].load(std::memory_order_relaxed))
          wanted.push_back({&p, L, i});
  }
  update(camera);  // queues them first (its figures are the unshown draw's: dropped)
  FirstView fv{int(wanted.size()), 0};
  for (;;) {
    fv.still_missing = 0;
    for (const Wanted& w : wanted) {
      const State s = w.p->state[std::size_t(w.level)][w.i];
      fv.still_missing += s != State::kResident && s != State::kFailed;
    }
    if (fv.still_missing == 0 || std::chrono::steady_clock::now() >= deadline) return fv;
    for (StreamingTiles* t = this; t; t = t->p_->fine.get()) {
      Impl& p = *t->p_;
      {
        std::unique_lock lk(p.m);
        p.idle_cv.wait_until(lk, std::min(deadline, std::chrono::steady_clock::now() +
                                                        std::chrono::milliseconds(5)));
      }
      p.install();
    }
  }
}

std::size_t StreamingTiles::pinned_bytes() const {
  return p_->pinned + (p_->fine ? p_->fine->pinned_bytes() : 0);
}
int StreamingTiles::failed_tiles() const {
  return p_->failed + (p_->fine ? p_->fine->failed_tiles() : 0);
}
int StreamingTiles::injected_faults() const {
  return p_->injected.load() + (p_->fine ? p_->fine->injected_faults() : 0);
}

}  // namespace terrasprite
