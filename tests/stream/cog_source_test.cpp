// SPDX-License-Identifier: MIT
// An existing COG as a streamed terrain (open_cog, bench stream --cog): each
// level reads the overview it should, at that overview's pixel centres, as
// GDAL reads the same window; the bounds computed at open bound every level's
// samples (cubic overviews overshoot); the bench flies it; bad inputs are one
// line and exit 2 with no output directory.
#include "stream/cog_source.h"

#include <gdal.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "stream/tile_file.h"
#include "terrasprite/common/cache_entry.h"
#include "terrasprite/common/error.h"
#include "terrasprite/stream/tiled_terrain.h"
#include "test_util.h"

namespace terrasprite {
namespace {

float height_at(int x, int y) {  // ridges sharp enough that cubic overviews overshoot
  return 100.f + 60.f * std::sin(float(x) * 0.09f) * std::cos(float(y) * 0.07f) +
         (((x / 16) + (y / 16)) % 2 ? 25.f : 0.f);
}

struct Raster {
  std::string driver = "COG";
  std::vector<std::string> options;
  int bands = 1;
  GDALDataType type = GDT_Float32;
  std::vector<int> overviews;  // GTiff: factors built after writing
};

// Writes an n x n raster at `path` (30 m, no CRS) and returns the path.
std::string make_raster(const std::filesystem::path& path, int n, const Raster& r) {
  GDALAllRegister();
  GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", n, n, r.bands, r.type, nullptr);
  double gt[6] = {500000, 30, 0, 4000000, 0, -30};
  GDALSetGeoTransform(mem, gt);
  std::vector<float> v(std::size_t(n) * n);
  for (int b = 1; b <= r.bands; ++b) {
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        v[std::size_t(y) * n + x] =
            r.bands == 1 ? height_at(x, y) : float((x * 3 + y * b * 5) % 256);
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(mem, b), GF_Write, 0, 0, n, n, v.data(), n, n,
                           GDT_Float32, 0, 0),
              CE_None);
  }
  std::vector<const char*> opts;
  for (const auto& o : r.options) opts.push_back(o.c_str());
  opts.push_back(nullptr);
  GDALDatasetH out = GDALCreateCopy(GDALGetDriverByName(r.driver.c_str()), path.c_str(), mem, FALSE,
                                    const_cast<char**>(opts.data()), nullptr, nullptr);
  EXPECT_NE(out, nullptr) << path;
  if (out && !r.overviews.empty()) {
    EXPECT_EQ(
        GDALBuildOverviews(out, "AVERAGE", int(r.overviews.size()),
                           const_cast<int*>(r.overviews.data()), 0, nullptr, nullptr, nullptr),
        CE_None);
  }
  if (out) GDALClose(out);
  GDALClose(mem);
  return path.string();
}

std::string make_cog(const std::filesystem::path& path, int n, const char* resampling = "CUBIC",
                     int block = 128) {
  return make_raster(path, n,
                     {"COG",
                      {"BLOCKSIZE=" + std::to_string(block), "COMPRESS=DEFLATE",
                       std::string("OVERVIEW_RESAMPLING=") + resampling}});
}

// Every sample of level L' is under the bound of the cell holding it at
// every bound level L >= L' + 2 (and level 0's samples under level 0's).
void expect_bounds_hold(const TileSetInfo& set) {
  TileFile file(set);
  std::vector<TileData> level(std::size_t(set.grid.bound_levels));
  for (int L = 0; L < set.grid.bound_levels; ++L) {
    std::string error;
    ASSERT_TRUE(file.read_level(L, level[std::size_t(L)], error)) << error;
  }
  for (int Ls = 0; Ls <= set.grid.coarsest_level; ++Ls) {
    const TileBlock& s = level[std::size_t(Ls)].block;
    for (int L = Ls == 0 ? 0 : Ls + 2; L < set.grid.bound_levels; L += (L == 0 ? 2 : 1)) {
      const TileBlock& b = level[std::size_t(L)].block;
      int bad = 0;
      for (int j = 0; j < s.h; ++j)
        for (int i = 0; i < s.w; ++i) {
          const int X = std::min(i << Ls, set.grid.width - 1),
                    Y = std::min(j << Ls, set.grid.height - 1);
          const int a = std::min(X >> L, set.tiles_cells_w(L) - 1),
                    c = std::min(Y >> L, set.tiles_cells_h(L) - 1);
          const bool over = s.height[std::size_t(j) * s.stride + i] >
                            b.bound[std::size_t(c) * b.bound_stride + a];
          if (over && bad == 0)
            ADD_FAILURE() << "level " << Ls << " sample " << i << "," << j << " = "
                          << s.height[std::size_t(j) * s.stride + i] << " > bound "
                          << b.bound[std::size_t(c) * b.bound_stride + a] << " of cell " << a << ","
                          << c << " at level " << L;
          bad += over;
        }
      EXPECT_EQ(bad, 0) << "samples of level " << Ls << " above the bounds of level " << L;
    }
  }
}

TEST(CogSource, TilesAreGdalReadsOfTheSelectedOverviewAtPixelCentres) {
  tstest::TempDir t;
  std::filesystem::create_directories(t.path);
  const std::string cog = make_cog(t.path / "dem.tif", 513);
  const TileSetInfo set = open_cog(cog);
  ASSERT_TRUE(set.cog);
  const auto& rs = set.cog->height_rasters;
  ASSERT_GE(rs.size(), 3u);               // the COG driver's own overviews: 257, 129, 65
  EXPECT_EQ(set.grid.coarsest_level, 8);  // 513, 257, ..., 3: the in-memory pyramid's levels
  EXPECT_NEAR(set.grid.spacing_x, 30.0, 1e-9);
  GDALDatasetH ds = GDALOpen(cog.c_str(), GA_ReadOnly);
  ASSERT_NE(ds, nullptr);
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  TileFile file(set);
  for (int L = 0; L <= set.grid.coarsest_level; ++L) {
    const int r =
        std::min<int>(L, int(rs.size()) - 1);  // overview L - 1 while one exists, then the coarsest
    ASSERT_EQ(cog_raster_for_level(rs, L), r) << "level " << L;
    GDALRasterBandH rb = r == 0 ? band : GDALGetOverview(band, r - 1);
    const int rw = GDALGetRasterBandXSize(rb), rh = GDALGetRasterBandYSize(rb);
    std::vector<float> px(std::size_t(rw) * rh);
    ASSERT_EQ(GDALRasterIO(rb, GF_Read, 0, 0, rw, rh, px.data(), rw, rh, GDT_Float32, 0, 0),
              CE_None);
    // Vertex-aligned sample i of level L sits at level-0 index i 2^L, i.e.
    // at (i 2^L + 0.5) rw / W - 0.5 in the overview's pixel centres.
    auto at = [&](int i, int n0, int n) {
      const double X = std::min(double(i << L), double(n0 - 1));
      return std::clamp((X + 0.5) * n / n0 - 0.5, 0.0, double(n - 1));
    };
    for (int ty = 0; ty < set.tiles_y[std::size_t(L)]; ++ty)
      for (int tx = 0; tx < set.tiles_x[std::size_t(L)]; ++tx) {
        TileData d;
        std::string error;
        ASSERT_TRUE(file.read(L, tx, ty, d, error)) << error;
        const TileBlock& b = d.block;
        ASSERT_EQ(b.x0, tx * 128);
        ASSERT_EQ(b.y0, ty * 128);
        if (L == 0) {  // level 0 is the raster: GDAL's window exactly
          std::vector<float> w(std::size_t(b.w) * b.h);
          ASSERT_EQ(GDALRasterIO(band, GF_Read, b.x0, b.y0, b.w, b.h, w.data(), b.w, b.h,
                                 GDT_Float32, 0, 0),
                    CE_None);
          EXPECT_EQ(w, d.height) << "tile " << tx << "," << ty;
          continue;
        }
        double worst = 0;
        for (int j = 0; j < b.h; ++j)
          for (int i = 0; i < b.w; ++i) {
            const double u = at(b.x0 + i, set.grid.width, rw),
                         v = at(b.y0 + j, set.grid.height, rh);
            const int u0 = int(u), v0 = int(v), u1 = std::min(u0 + 1, rw - 1),
                      v1 = std::min(v0 + 1, rh - 1);
            auto p = [&](int x, int y) { return double(px[std::size_t(y) * rw + x]); };
            const double want = (p(u0, v0) * (u0 + 1 - u) + p(u1, v0) * (u - u0)) * (v0 + 1 - v) +
                                (p(u0, v1) * (u0 + 1 - u) + p(u1, v1) * (u - u0)) * (v - v0);
            worst = std::max(worst, std::abs(want - b.height[std::size_t(j) * b.stride + i]));
          }
        EXPECT_LT(worst, 1e-3) << "level " << L << " tile " << tx << "," << ty;
      }
  }
  GDALClose(ds);
  expect_bounds_hold(set);
}

TEST(CogSource, EachLevelReadsItsOverviewAndTheBoundsCoverThemAll) {
  // A tiled GeoTIFF whose overviews hold constants, so a level shows which it read.
  tstest::TempDir t;
  std::filesystem::create_directories(t.path);
  const std::string tif = make_raster(
      t.path / "ovr.tif", 257,
      {"GTiff", {"TILED=YES", "BLOCKXSIZE=64", "BLOCKYSIZE=64"}, 1, GDT_Float32, {2, 4}});
  {
    GDALDatasetH ds = GDALOpen(tif.c_str(), GA_Update);
    ASSERT_NE(ds, nullptr);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    ASSERT_EQ(GDALGetOverviewCount(band), 2);
    for (int k = 0; k < 2; ++k) {
      GDALRasterBandH o = GDALGetOverview(band, k);
      const int w = GDALGetRasterBandXSize(o), h = GDALGetRasterBandYSize(o);
      std::vector<float> c(std::size_t(w) * h, 1000.f * float(k + 1));
      ASSERT_EQ(GDALRasterIO(o, GF_Write, 0, 0, w, h, c.data(), w, h, GDT_Float32, 0, 0), CE_None);
    }
    GDALClose(ds);
  }
  for (long long held : {1LL << 22, 1024LL}) {  // all bound levels held; from level 3 up only
    const TileSetInfo set = open_cog(tif, "", 4, held);
    EXPECT_EQ(set.cog->bound_from, held == 1024 ? 3 : 0);
    TileFile file(set);
    for (int L = 1; L <= set.grid.coarsest_level; ++L) {
      TileData d;
      std::string error;
      ASSERT_TRUE(file.read(L, 0, 0, d, error)) << error;
      const float want = L == 1 ? 1000.f : 2000.f;
      for (float v : d.height) ASSERT_NEAR(v, want, 1e-2) << "level " << L;
    }
    expect_bounds_hold(set);  // the overviews' 1000s and 2000s are in the bounds
    EXPECT_GE(set.tile_max[std::size_t(set.grid.bound_levels - 1)][0], 2000.f);
  }
}

TEST(CogSource, BenchStreamFliesACogAndRefusesBadOnesWithExit2) {
  tstest::TempDir t;
  std::filesystem::create_directories(t.path);
  // 32-cell tiles; 16 MB pins the whole terrain, so every frame compares with the in-memory one.
  const std::string cog = make_cog(t.path / "dem.tif", 257, "AVERAGE", 32);
  const std::string tex = make_raster(
      t.path / "tex.tif", 257, {"COG", {"BLOCKSIZE=128", "COMPRESS=DEFLATE"}, 3, GDT_Byte, {}});
  auto r = tstest::run_cli("bench stream --cog " + cog + " --texture " + tex +
                           " --cache-mb 16 --size 96x64 --frames 8 --json " + (t / "s.json") +
                           " --out " + (t / "s"));
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(t / "s.json"));
  EXPECT_EQ(j["terrain"]["samples"][0], 257);
  EXPECT_GT(j["cog"]["bounds_ms"].get<double>(), 0.0);  // one pass over the overviews
  EXPECT_EQ(j["images_equal_when_resident"]["frames_compared"],
            j["images_equal_when_resident"]["frames_equal"]);
  EXPECT_GT(j["images_equal_when_resident"]["frames_compared"].get<int>(), 0);
  EXPECT_EQ(j["per_frame"].size(), 8u);
  EXPECT_EQ(j["terrain"]["tile_cells"], 32);  // the COG's blocks

  std::ofstream(t / "text.tif") << "not a raster";
  const std::string strips =
      make_raster(t.path / "strips.tif", 257, {"GTiff", {}, 1, GDT_Float32, {2, 4}});
  const std::string flat =
      make_raster(t.path / "flat.tif", 257, {"GTiff", {"TILED=YES"}, 1, GDT_Float32, {}});
  const std::string small_tex =
      make_raster(t.path / "small.tif", 129, {"COG", {}, 3, GDT_Byte, {}});
  for (const auto& [args, named] : std::vector<std::pair<std::string, std::string>>{
           {"--cog " + (t / "text.tif"), t / "text.tif"},
           {"--cog " + (t / "missing.tif"), t / "missing.tif"},
           {"--cog " + strips, strips},
           {"--cog " + flat, flat},
           {"--cog " + tex, tex},
           {"--cog " + cog + " --texture " + small_tex, small_tex},
           {"--cog " + cog + " --tiles " + (t / "s"), "--tiles"}}) {
    r = tstest::run_cli("bench stream " + args + " --frames 2 --size 32x24 --out " + (t / "bad"));
    EXPECT_EQ(r.status, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(std::filesystem::exists(t.path / "bad")) << args;
  }
}

// The bounds pass's result is cached (under TERRASPRITE_CACHE): a second open
// of the same file reads it back, equal; a changed file computes it afresh.
TEST(CogSource, BoundsAreCachedForAnUnchangedFileOnly) {
  tstest::TempDir t;
  std::filesystem::create_directories(t.path);
  const std::string cog = make_cog(t.path / "dem.tif", 257);
  const std::string root = t / "cache", dir = (t.path / "cache" / "cog-bounds").string();
  const char* was = std::getenv("TERRASPRITE_CACHE");  // ctest sets one for every test
  const std::string before = was ? was : "";
  ASSERT_EQ(setenv("TERRASPRITE_CACHE", root.c_str(), 1), 0);
  const TileSetInfo a = open_cog(cog, "", 4, 1 << 10);
  const TileSetInfo b = open_cog(cog, "", 4, 1 << 10);
  EXPECT_FALSE(a.cog->bounds_cached);
  EXPECT_TRUE(b.cog->bounds_cached);
  EXPECT_EQ(a.cog->bound_from, b.cog->bound_from);
  EXPECT_EQ(a.cog->bound, b.cog->bound);
  EXPECT_EQ(a.tile_max, b.tile_max);
  EXPECT_EQ(a.grid.max_height, b.grid.max_height);
  EXPECT_EQ(a.grid.min_height, b.grid.min_height);
  // Another held level is another key.
  EXPECT_FALSE(open_cog(cog, "", 4, 1 << 22).cog->bounds_cached);
  // The file rewritten (another size and time): computed again, then cached.
  std::filesystem::remove(cog);
  make_cog(t.path / "dem.tif", 129);
  std::filesystem::last_write_time(cog,
                                   std::filesystem::last_write_time(cog) + std::chrono::seconds(5));
  EXPECT_FALSE(open_cog(cog, "", 4, 1 << 10).cog->bounds_cached);
  EXPECT_TRUE(open_cog(cog, "", 4, 1 << 10).cog->bounds_cached);
  // A damaged cache file is ignored, never an error.
  for (const auto& e : std::filesystem::directory_iterator(dir))
    std::filesystem::resize_file(e.path(), 40);
  EXPECT_FALSE(open_cog(cog, "", 4, 1 << 10).cog->bounds_cached);
  if (was)
    ASSERT_EQ(setenv("TERRASPRITE_CACHE", before.c_str(), 1), 0);
  else
    ASSERT_EQ(unsetenv("TERRASPRITE_CACHE"), 0);
}

}  // namespace
}  // namespace terrasprite

namespace terrasprite {
namespace {

// TERRASPRITE_CACHE set to `root` for a scope, then restored.
struct CacheRootScope {
  std::string before;
  bool was;
  explicit CacheRootScope(const std::string& root) {
    const char* b = std::getenv("TERRASPRITE_CACHE");
    was = b != nullptr;
    before = b ? b : "";
    setenv("TERRASPRITE_CACHE", root.c_str(), 1);
  }
  ~CacheRootScope() {
    if (was)
      setenv("TERRASPRITE_CACHE", before.c_str(), 1);
    else
      unsetenv("TERRASPRITE_CACHE");
  }
};

std::vector<std::filesystem::path> entries(const std::string& dir) {
  std::vector<std::filesystem::path> v;
  for (const auto& e : std::filesystem::directory_iterator(dir)) v.push_back(e.path());
  return v;
}

// The bounds of the file `path` computed afresh (under an empty cache root).
std::vector<std::vector<float>> fresh_bounds(const std::string& path, const std::string& root) {
  std::filesystem::remove_all(root);
  const CacheRootScope scope(root);
  const TileSetInfo s = open_cog(path, "", 4, 1 << 10);
  EXPECT_FALSE(s.cog->bounds_cached);
  return s.cog->bound;
}

// Another DEM copied over the cached one, same path, same size, its old
// modification time restored: the fingerprint (change time, edge hash) sees
// it and the bounds are computed again, not read. Cost: about 0.3 s.
TEST(CogBoundsCache, AnotherFileAtTheSamePathSizeAndTimeIsAMiss) {
  tstest::TempDir t;
  const std::string a = make_cog(t.path / "a.tif", 257, "CUBIC");
  const std::string b = make_cog(t.path / "b.tif", 257, "AVERAGE");
  const auto size = std::max(std::filesystem::file_size(a), std::filesystem::file_size(b));
  std::filesystem::resize_file(a, size);  // bytes after a TIFF's last block are never read
  std::filesystem::resize_file(b, size);
  const auto b_bounds = fresh_bounds(b, t / "fresh");
  ASSERT_NE(fresh_bounds(a, t / "fresh"), b_bounds) << "the test needs two different DEMs";

  const CacheRootScope scope(t / "cache");
  EXPECT_FALSE(open_cog(a, "", 4, 1 << 10).cog->bounds_cached);
  ASSERT_TRUE(open_cog(a, "", 4, 1 << 10).cog->bounds_cached);
  const auto mtime = std::filesystem::last_write_time(a);
  std::filesystem::copy_file(b, a, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::last_write_time(a, mtime);
  const TileSetInfo now = open_cog(a, "", 4, 1 << 10);
  EXPECT_FALSE(now.cog->bounds_cached) << "the old file's bounds read for the new one";
  EXPECT_EQ(now.cog->bound, b_bounds);
}

// Another file's entry under this file's name, a flipped payload byte, and
// an entry of the right key whose bounds no pass makes (-1e30 everywhere:
// rays would hit nothing) are each a note and a fresh pass, never used.
TEST(CogBoundsCache, AWrongKeyADamagedOrAnImpossibleEntryIsAMiss) {
  tstest::TempDir t;
  const std::string a = make_cog(t.path / "a.tif", 257, "CUBIC");
  const std::string b = make_cog(t.path / "b.tif", 257, "AVERAGE");
  const auto a_bounds = fresh_bounds(a, t / "fresh");
  const std::string dir = t / "cache/cog-bounds";
  const CacheRootScope scope(t / "cache");
  (void)open_cog(b, "", 4, 1 << 10);
  const std::filesystem::path b_entry = entries(dir).at(0);
  std::filesystem::rename(b_entry, t.path / "b.entry");
  (void)open_cog(a, "", 4, 1 << 10);
  const std::filesystem::path a_entry = entries(dir).at(0);
  const auto reopen = [&](const char* note) {
    testing::internal::CaptureStderr();
    const TileSetInfo s = open_cog(a, "", 4, 1 << 10);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_FALSE(s.cog->bounds_cached) << note;
    EXPECT_EQ(s.cog->bound, a_bounds) << note;
    EXPECT_NE(err.find(note), std::string::npos) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_TRUE(open_cog(a, "", 4, 1 << 10).cog->bounds_cached) << "rebuilt and replaced";
  };

  std::filesystem::copy_file(t.path / "b.entry", a_entry,
                             std::filesystem::copy_options::overwrite_existing);
  reopen("other inputs");

  const auto size = std::filesystem::file_size(a_entry);
  {
    std::fstream f(a_entry, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(std::streamoff(size - 8));
    const char c = char(f.get());
    f.seekp(std::streamoff(size - 8));
    f.put(char(c ^ 1));
  }
  reopen("checksum");

  // Rewritten with the right key and a valid checksum, bounds of -1e30.
  std::ifstream in(a_entry, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  in.close();
  std::uint32_t key_size = 0;
  std::memcpy(&key_size, bytes.data() + 12, 4);
  const std::string key = bytes.substr(16, key_size);
  std::optional<std::string> payload = read_cache_entry(a_entry, key, 1 << 30).payload;
  ASSERT_TRUE(payload);
  std::vector<float> v(payload->size() / 4);
  std::memcpy(v.data(), payload->data(), payload->size());
  std::fill(v.begin() + 2, v.end(), -1e30f);
  std::ofstream(a_entry, std::ios::binary | std::ios::trunc) << encode_cache_entry(
      key, std::string_view(reinterpret_cast<const char*>(v.data()), v.size() * 4));
  reopen("bounds no pass can make");
}

}  // namespace
}  // namespace terrasprite
