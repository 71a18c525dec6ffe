// SPDX-License-Identifier: MIT
// Tiled terrain on disk and the streaming source: tiles and overviews match
// GDAL's own windowed reads and the in-memory pyramid, the cache holds its
// budget, a stalled or failing loader never stops a frame, and a streamed
// image equals the in-memory one once its tiles are resident.
#include "terrasprite/stream/streaming_tiles.h"

#include <gdal.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>

#include "stream/tile_file.h"
#include "stream_test_util.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/stream/tiled_terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "test_util.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {
namespace {

constexpr int kW = 160, kH = 120;  // rendered frames: tiny on purpose

Terrain small_terrain(int n) {
  TerrainOptions o;
  o.synthetic_size = n;
  o.erosion_passes = 0;
  return load_terrain(o);
}

// A tiled terrain of n x n samples in 16-cell tiles, lossless colour.
struct TiledFixture {
  tstest::TempDir dir;
  Terrain terrain;
  std::unique_ptr<VoxelTerrain> vt;
  TileSetInfo set;
  explicit TiledFixture(int n)
      : terrain(small_terrain(n)), vt(std::make_unique<VoxelTerrain>(terrain)) {
    TileWriteOptions o;
    o.tile_log2 = 4;
    o.color_compress = "DEFLATE";
    write_tiled_terrain(*vt, std::nullopt, dir.path.string(), o);
    set = read_tile_set(dir.path.string());
  }
};

std::vector<Camera> path(const Terrain& t, int frames) {
  return low_fast_path(t.heights, frames, double(kW) / kH);
}

TEST(TiledTerrain, OverviewsAreTheVertexAlignedLevelsAndTilesMatchGdalWindows) {
  TiledFixture f(
      77);  // 77 - 1 = 76 cells: GDAL's own overviews would be 39, 20, ... not 39, 20, 11
  const VoxelTerrain::Data& d = f.vt->data();
  ASSERT_EQ(f.set.grid.coarsest_level, int(d.levels.size()) - 1);
  GDALDatasetH hds = GDALOpen(f.set.height_file().c_str(), GA_ReadOnly);
  ASSERT_NE(hds, nullptr);
  GDALRasterBandH band = GDALGetRasterBand(hds, 1);
  ASSERT_EQ(GDALGetOverviewCount(band), f.set.grid.coarsest_level);
  TileFile file(f.set);
  for (int L = 0; L < f.set.grid.bound_levels; ++L) {
    GDALRasterBandH lb = nullptr;
    if (L <= f.set.grid.coarsest_level) lb = L == 0 ? band : GDALGetOverview(band, L - 1);
    if (lb) {
      EXPECT_EQ(GDALGetRasterBandXSize(lb), d.levels[std::size_t(L)].w) << "level " << L;
      EXPECT_EQ(GDALGetRasterBandYSize(lb), d.levels[std::size_t(L)].h) << "level " << L;
    }
    for (int ty = 0; ty < f.set.tiles_y[std::size_t(L)]; ++ty)
      for (int tx = 0; tx < f.set.tiles_x[std::size_t(L)]; ++tx) {
        TileData t;
        std::string error;
        ASSERT_TRUE(file.read(L, tx, ty, t, error)) << error;
        const TileBlock* mem = f.vt->level_block(L);
        const TileBlock& b = t.block;
        EXPECT_EQ(b.x0, tx * 16);
        EXPECT_EQ(b.y0, ty * 16);
        EXPECT_LE(
            b.max_height,
            f.set.tile_max[std::size_t(L)][std::size_t(ty) * f.set.tiles_x[std::size_t(L)] + tx]);
        std::vector<float> gdal(std::size_t(b.w) * b.h);
        if (lb) {
          ASSERT_EQ(GDALRasterIO(lb, GF_Read, b.x0, b.y0, b.w, b.h, gdal.data(), b.w, b.h,
                                 GDT_Float32, 0, 0),
                    CE_None);
        }
        for (int j = 0; j < b.h - 1; ++j)
          for (int i = 0; i < b.w - 1; ++i) {
            ASSERT_EQ(b.bound[j * b.bound_stride + i],
                      mem->bound[(b.y0 + j) * mem->bound_stride + b.x0 + i]);
          }
        if (!lb) continue;
        for (int j = 0; j < b.h; ++j)
          for (int i = 0; i < b.w; ++i) {
            const std::size_t m = std::size_t(b.y0 + j) * mem->stride + b.x0 + i;
            ASSERT_EQ(b.height[j * b.stride + i], gdal[std::size_t(j) * b.w + i]);
            ASSERT_EQ(b.height[j * b.stride + i], mem->height[m]) << L << " " << i << "," << j;
            ASSERT_EQ(b.color[j * b.stride + i], mem->color[m]);
          }
      }
  }
  GDALClose(hds);
}

TEST(TiledTerrain, MissingFileIsAnInputError) {
  TiledFixture f(65);
  std::filesystem::remove(f.set.color_file());
  EXPECT_THROW(read_tile_set(f.set.dir), InputError);
  EXPECT_THROW(read_tile_set(f.dir / "nowhere"), InputError);
}

// Flies `cams` through a streaming source; calls check(stats) after every update.
template <class Check>
void fly(StreamingTiles& s, VoxelRenderer& r, const std::vector<Camera>& cams, Check check) {
  for (const Camera& c : cams) {
    check(s.update(c));
    r.draw(c);
  }
  check(s.update(cams.back()));
}

TEST(StreamingTiles, CacheNeverExceedsItsBudget) {
  TiledFixture f(257);
  StreamOptions o;
  o.cache_bytes = std::size_t(384) << 10;  // pinned levels + about a hundred 16-cell tiles
  o.pinned_share = 0;
  o.image_height = kH;
  StreamingTiles s(f.set, o);
  VoxelRenderer r(s, kW, kH);
  int evicted = 0, loaded = 0;
  std::vector<Camera> cams = path(f.terrain, 10);
  for (int k = 0; k < 10; ++k) {  // then turn around: the tiles ahead change
    Camera c = cams[std::size_t(k)];
    c.yaw_deg += 180;
    cams.push_back(c);
  }
  fly(s, r, cams, [&](const StreamFrameStats& st) {
    s.settle();
    ASSERT_LE(st.resident_bytes, o.cache_bytes);
    evicted += st.evicted;
    loaded += st.loaded;
  });
  EXPECT_GT(loaded, 0);
  EXPECT_GT(evicted, 0) << "the budget should have forced evictions on this path";
}

// Under a budget smaller than the footprint, prefetch evicts only tiles the
// last frame did not read: redrawing the last frame's view right after the
// next update reads nothing coarser, whenever that frame missed nothing.
// (Prefetch evicted tiles the march read wide of the footprint, which were
// then missed and reloaded frame after frame: 0.3% of 32769²'s reads.)
TEST(StreamingTiles, PrefetchNeverEvictsWhatTheLastFrameRead) {
  TiledFixture f(257);
  StreamOptions o;
  o.cache_bytes = std::size_t(640) << 10;
  o.pinned_share = 0;
  o.image_height = kH;
  StreamingTiles s(f.set, o);
  VoxelRenderer r(s, kW, kH);
  const std::vector<Camera> cams = path(f.terrain, 48);
  int evicted = 0, checked = 0;
  long long last_degraded = -1;
  for (std::size_t k = 0; k < cams.size(); ++k) {
    StreamFrameStats st = s.update(cams[k]);
    evicted += st.evicted;
    if (k > 0 && last_degraded == 0) {
      StreamFrameStats again;
      r.draw(cams[k - 1]);
      s.collect_reads(again);
      EXPECT_EQ(again.degraded_samples, 0) << "frame " << k << " evicted " << st.evicted;
      ++checked;
    }
    s.settle();
    r.draw(cams[k]);
    StreamFrameStats own;
    s.collect_reads(own);
    last_degraded = own.degraded_samples;
  }
  EXPECT_GT(evicted, 0) << "the budget should be under the footprint for this test to bite";
  // 6 of these 48 frames miss nothing (the path outruns this budget's
  // prefetch); when prefetch could evict them, none did.
  EXPECT_GT(checked, 0);
}

TEST(StreamingTiles, StalledLoaderNeverBlocksAFrame) {
  TiledFixture f(129);
  std::mutex m;
  std::condition_variable cv;
  bool release = false;
  StreamOptions o;
  o.image_height = kH;
  o.pinned_share = 0;
  o.before_read = [&](int, int, int) {
    std::unique_lock lk(m);
    cv.wait(lk, [&] { return release; });
  };
  long long degraded = 0;
  {
    StreamingTiles s(f.set, o);
    VoxelRenderer r(s, kW, kH);
    const auto t0 = std::chrono::steady_clock::now();
    fly(s, r, path(f.terrain, 4), [&](const StreamFrameStats& st) {
      degraded += st.degraded_samples;
      EXPECT_EQ(st.loaded, 0);
    });
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(60));
    {
      std::lock_guard lk(m);
      release = true;
    }
    cv.notify_all();
  }
  EXPECT_GT(degraded, 0);
}

// Before the first frame: the tiles an unshown draw missed are loaded, so the
// first frame reads (almost) nothing coarser; a stalled loader makes the wait
// end at its deadline instead of hanging.
TEST(StreamingTiles, FirstViewWaitsForTheTilesItMissedUntilItsDeadline) {
  TiledFixture f(129);
  StreamOptions o;
  o.image_height = kH;
  o.pinned_share = 0;
  const Camera c = path(f.terrain, 2).front();
  {
    StreamingTiles s(f.set, o);
    VoxelRenderer r(s, kW, kH);
    r.draw(c);  // unshown: marks what the view misses
    StreamFrameStats probe;
    s.collect_reads(probe);
    const auto fv =
        s.wait_for_first_view(c, std::chrono::steady_clock::now() + std::chrono::minutes(5));
    EXPECT_GT(fv.waited_for, 0);
    EXPECT_EQ(fv.still_missing, 0);
    StreamFrameStats first = s.update(c);
    r.draw(c);
    s.collect_reads(first);
    EXPECT_GT(probe.degraded_samples, 0);
    EXPECT_LT(first.degraded_samples * 10, probe.degraded_samples)
        << "the first frame should read what the unshown draw missed from its own level";
  }
  std::mutex m;
  std::condition_variable cv;
  bool release = false;
  o.before_read = [&](int, int, int) {
    std::unique_lock lk(m);
    cv.wait(lk, [&] { return release; });
  };
  {
    StreamingTiles s(f.set, o);
    VoxelRenderer r(s, kW, kH);
    r.draw(c);
    const auto fv =
        s.wait_for_first_view(c, std::chrono::steady_clock::now() + std::chrono::milliseconds(50));
    EXPECT_GT(fv.waited_for, 0);
    EXPECT_EQ(fv.still_missing, fv.waited_for)
        << "nothing could load: the wait ended at its deadline";
    {
      std::lock_guard lk(m);
      release = true;
    }
    cv.notify_all();
  }
}

TEST(StreamingTiles, InjectedReadFaultIsSurvivedAndCounted) {
  TiledFixture f(129);
  StreamOptions o;
  o.image_height = kH;
  o.pinned_share = 0;
  o.fail_read = [](int level, int tx, int) { return level == 0 && tx % 2 == 0; };
  StreamingTiles s(f.set, o);
  VoxelRenderer r(s, kW, kH);
  int failed = 0;
  const auto cams = path(f.terrain, 6);
  for (const Camera& c : cams) {
    failed += s.update(c).failed;
    s.settle();
    r.draw(c);
  }
  failed += s.update(cams.back()).failed;
  EXPECT_GT(failed, 0);
  EXPECT_EQ(failed, s.failed_tiles());
  EXPECT_EQ(s.injected_faults(), s.failed_tiles());
}

TEST(StreamingTiles, StreamedImageEqualsInMemoryOnceResident) {
  TiledFixture f(129);
  ResidentTiles mem(f.set);
  StreamOptions o;
  o.image_height = kH;
  o.pinned_share = 0;
  StreamingTiles s(f.set, o);
  VoxelRenderer rm(mem, kW, kH), rs(s, kW, kH);
  for (const Camera& c : path(f.terrain, 3)) {
    // Draw until a frame reads nothing coarser than it wanted.
    const StreamFrameStats st = stream_test::draw_until_resident(rs, s, c);
    ASSERT_EQ(st.degraded_samples, 0);
    const Frame a = rm.draw(c), b = rs.draw(c);
    ASSERT_EQ(a.color.rgba, b.color.rgba);
  }
}

}  // namespace
}  // namespace terrasprite
