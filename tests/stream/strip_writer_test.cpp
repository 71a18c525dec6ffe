// SPDX-License-Identifier: MIT
// The strip-wise tile writer equals the in-memory one: every level of
// height.tif, color.tif and bound.tif sample for sample, and tiles.json
// byte for byte, across band and tile edges and odd sizes.
#include <gdal.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "terrasprite/common/error.h"
#include "terrasprite/stream/tiled_terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "test_util.h"

namespace terrasprite {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Every level of `file` (the raster, then its overviews) as bytes.
std::vector<std::vector<unsigned char>> levels_of(const std::filesystem::path& file) {
  GDALDatasetH ds = GDALOpen(file.string().c_str(), GA_ReadOnly);
  EXPECT_NE(ds, nullptr) << file;
  if (!ds) return {};
  const int bands = GDALGetRasterCount(ds);
  GDALRasterBandH b1 = GDALGetRasterBand(ds, 1);
  const GDALDataType type = GDALGetRasterDataType(b1);
  const int px = GDALGetDataTypeSizeBytes(type);
  std::vector<std::vector<unsigned char>> out;
  for (int k = -1; k < GDALGetOverviewCount(b1); ++k) {
    std::vector<unsigned char> level;
    for (int b = 1; b <= bands; ++b) {
      GDALRasterBandH band = GDALGetRasterBand(ds, b);
      if (k >= 0) band = GDALGetOverview(band, k);
      const int w = GDALGetRasterBandXSize(band), h = GDALGetRasterBandYSize(band);
      std::vector<unsigned char> v(std::size_t(w) * h * px);
      EXPECT_EQ(GDALRasterIO(band, GF_Read, 0, 0, w, h, v.data(), w, h, type, 0, 0), CE_None);
      level.insert(level.end(), v.begin(), v.end());
    }
    out.push_back(std::move(level));
  }
  GDALClose(ds);
  return out;
}

void expect_same_tile_sets(const std::filesystem::path& a, const std::filesystem::path& b) {
  for (const char* f : {"height.tif", "color.tif", "bound.tif"}) {
    const auto la = levels_of(a / f), lb = levels_of(b / f);
    ASSERT_EQ(la.size(), lb.size()) << f;
    for (std::size_t k = 0; k < la.size(); ++k) EXPECT_TRUE(la[k] == lb[k]) << f << " level " << k;
  }
  EXPECT_EQ(slurp(a / "tiles.json"), slurp(b / "tiles.json"));
  EXPECT_FALSE(std::filesystem::exists(b / ".strips"));
}

struct Case {
  int synthetic, resample, tile_log2, band_rows;
  double exaggeration;
  const char* texture;
  const char* color;
};

void check_case(const Case& c) {
  TerrainOptions to;
  to.synthetic_size = c.synthetic;
  to.resample = c.resample;
  to.erosion_passes = 0;
  to.exaggeration = c.exaggeration;
  to.texture = c.texture;
  TileWriteOptions wo;
  wo.tile_log2 = c.tile_log2;
  wo.color_compress = c.color;
  tstest::TempDir t;
  std::filesystem::create_directories(t.path / "mem");
  std::filesystem::create_directories(t.path / "strips");
  {
    const Terrain terrain = load_terrain(to);
    write_tiled_terrain(VoxelTerrain(terrain), std::nullopt, (t.path / "mem").string(), wo);
  }
  const LargeTerrain large = load_large_terrain(to);
  const StripWriteStats s = write_tiled_terrain_strips(
      terrain_rows(large), std::nullopt, (t.path / "strips").string(), wo, c.band_rows);
  EXPECT_GT(s.temp_bytes, 0);
  expect_same_tile_sets(t.path / "mem", t.path / "strips");
}

TEST(StripWriter, EqualsTheInMemoryWriterAcrossBandsTilesAndOddSizes) {
  // 77: 76 cells, levels 39, 20, 11, 6, 4, 3 (clamped edges at every level);
  // 16-row bands cut level 0 five times; 16-cell tiles.
  check_case({65, 77, 4, 16, 1.0, "derived", "DEFLATE"});
  // Exaggerated heights and the checker texture, 32-row bands of 32-cell tiles.
  check_case({33, 130, 5, 32, 1.5, "checker", "DEFLATE"});
}

TEST(StripWriter, EqualsTheInMemoryWriterWithJpegColourAndAutomaticBands) {
  // 1025 rows: one automatic 1024-row band and one of a single row, 128-cell
  // tiles, the default lossy colour (equal pixels, equal JPEG tiles).
  check_case({129, 1025, 7, 0, 1.0, "derived", "JPEG"});
}

TEST(StripWriter, RefusesInsetsAndBandsAcrossTiles) {
  TerrainOptions to;
  to.synthetic_size = 33;
  to.erosion_passes = 0;
  const LargeTerrain large = load_large_terrain(to);
  tstest::TempDir t;
  TileWriteOptions wo;
  wo.tile_log2 = 4;
  EXPECT_THROW(
      write_tiled_terrain_strips(terrain_rows(large), std::nullopt, t.path.string(), wo, 24),
      InputError);
  wo.insets.push_back({});
  EXPECT_THROW(write_tiled_terrain_strips(terrain_rows(large), std::nullopt, t.path.string(), wo),
               InputError);
}

TEST(LargeTerrain, RefusesAResampleBeyondItsLimitBeforeWork) {
  TerrainOptions to;
  to.synthetic_size = 33;
  to.resample = kMaxLargeResample + 1;
  EXPECT_THROW(load_large_terrain(to), InputError);
  to.resample = 1;
  EXPECT_THROW(load_large_terrain(to), InputError);
}

}  // namespace
}  // namespace terrasprite
