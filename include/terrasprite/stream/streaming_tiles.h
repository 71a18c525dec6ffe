// SPDX-License-Identifier: MIT
// Out-of-core terrain for the ray caster (Cohen-Or et al., "A real-time
// photo-realistic visual flythrough", section on the terrain database): tiles
// of a tiled terrain on disk (terrasprite/stream/tiled_terrain.h) cached under a byte
// budget, loaded by I/O threads ahead of need (the camera's footprint at each
// level, grown by a margin and pushed along the motion), and never waited
// for: a frame reads the finest resident ancestor where a tile is missing.
#pragma once
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "terrasprite/camera/camera.h"
#include "terrasprite/voxel/terrain_tiles.h"
#include "terrasprite/stream/tiled_terrain.h"

namespace terrasprite {

struct StreamOptions {
  std::size_t cache_bytes = std::size_t(256) << 20;  ///< resident + in-flight tiles, bytes
  int io_threads = 2;                                ///< loader threads (each its own GDAL handles)
  /// GDAL's block cache (GDAL_CACHEMAX), set process-wide at construction.
  std::size_t gdal_cache_bytes = std::size_t(32) << 20;
  /// Pinned coarse levels (loaded at start, never evicted) may take this
  /// share of the budget; the coarsest sample level and every bound-only
  /// level are pinned whatever it says.
  double pinned_share = 0.125;
  double margin = 1.5;           ///< footprint radius and wedge grown by this factor
  double lookahead_frames = 30;  ///< the footprint is also taken this many frames ahead
  /// The renderer's level rule (VoxelOptions::pixel_voxel_ratio) and image
  /// height in pixels, so the footprint asks each level where it is read.
  double pixel_voxel_ratio = 1.0;
  int image_height = 1080;
  /// A share (0..1) of tile reads made to fail, chosen by a hash of the tile
  /// (so runs repeat); the environment variable TERRASPRITE_STREAM_FAULTS
  /// overrides it when set.
  double fault_rate = 0.0;
  /// With fine levels (insets), their tiles get this share of cache_bytes
  /// (a cache of their own, same loaders' count, same rules); the base the rest.
  double fine_share = 0.5;
  /// Test hooks, called on a loader thread before each read: `before_read`
  /// may block (a stalled disk); `fail_read` returning true fails the read.
  /// Levels and tiles are the renderer's (the combined grid with fine levels).
  std::function<void(int level, int tx, int ty)> before_read;
  std::function<bool(int level, int tx, int ty)> fail_read;
};

/// What happened in one frame (between two update() calls).
struct StreamFrameStats {
  long long degraded_samples = 0;  ///< reads served coarser than the march asked
  long long lookups = 0;           ///< tile lookups by the renderer (hits + misses)
  long long misses = 0;            ///< lookups of tiles not resident
  int requested = 0;               ///< tiles newly queued for loading
  int loaded = 0;                  ///< tiles installed by this update
  int evicted = 0;
  int failed = 0;                  ///< reads that failed (served coarser from now on)
  long long bytes_read = 0;        ///< tile bytes decoded from disk
  std::size_t resident_bytes = 0;  ///< after the update, in-flight reservations included
  int resident_tiles = 0;
};

/// A TerrainTiles over a tiled terrain on disk. grid() and tile() follow
/// TerrainTiles (any threads, during a frame); update() is called between
/// frames by the owner (one thread), never waits for I/O, and is the only
/// point where tiles appear or disappear. Throws InputError at construction
/// when a file cannot be read (the pinned levels are read then).
class StreamingTiles final : public TerrainTiles {
 public:
  StreamingTiles(const TileSetInfo& set, StreamOptions options = {});
  ~StreamingTiles() override;
  StreamingTiles(const StreamingTiles&) = delete;
  StreamingTiles& operator=(const StreamingTiles&) = delete;

  const TerrainGrid& grid() const override;
  const TileBlock* tile(int level, int tx, int ty) const override;

  /// Between frames: installs finished loads, ends the last frame's
  /// counters, queues the footprint of `camera` (and its motion since the
  /// previous call), evicting least-recently-used tiles far from the camera
  /// to stay within the budget. Returns the last frame's figures.
  StreamFrameStats update(const Camera& camera);
  /// Adds the renderer's lookups and misses since the last update() or
  /// collect_reads() to `stats` (degraded_samples = misses): call after a
  /// frame to have its own reads in the stats update() returned before it.
  void collect_reads(StreamFrameStats& stats) const;
  /// Waits until every queued read is done and installs them (tests; the
  /// bench's "once resident" check). Returns the tiles installed.
  int settle();
  /// Before the first frame is shown, after a draw at `camera` that is not
  /// shown (its reads mark the tiles that view misses): updates for
  /// `camera`, which queues those tiles first, and waits until they are in
  /// (loaded or failed) or `deadline` passes, installing them as they land.
  /// So the first frames are drawn from the tiles they read, not from the
  /// pinned levels, at a bounded cost in time to first frame. Returns the
  /// tiles waited for and how many were still missing at the end.
  struct FirstView {
    int waited_for = 0;
    int still_missing = 0;
  };
  FirstView wait_for_first_view(const Camera& camera,
                                std::chrono::steady_clock::time_point deadline);

  std::size_t pinned_bytes() const;
  int failed_tiles() const;     ///< reads that failed so far
  int injected_faults() const;  ///< of those, failed by fault_rate or fail_read

 private:
  struct Impl;
  std::unique_ptr<Impl> p_;
};

/// The same tiled terrain wholly in memory (every level read at start, each
/// level one block): the in-memory source a streamed run is compared with.
class ResidentTiles final : public TerrainTiles {
 public:
  explicit ResidentTiles(const TileSetInfo& set);
  ~ResidentTiles() override;
  const TerrainGrid& grid() const override;
  const TileBlock* tile(int level, int tx, int ty) const override;
  const TileBlock* level_block(int level) const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> p_;
};

}  // namespace terrasprite
