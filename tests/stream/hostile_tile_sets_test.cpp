// SPDX-License-Identifier: MIT
// Tile sets, COGs and insets that lie: each is refused where it enters with
// one message naming the file and what is wrong, before any tile is read.
#include <gdal.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "stream/cog_source.h"
#include "stream_test_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/stream/insets.h"
#include "terrasprite/stream/tiled_terrain.h"
#include "terrasprite/terrain/terrain.h"
#include "test_util.h"

namespace terrasprite {
namespace {

namespace fs = std::filesystem;

// The message read_tile_set throws for `dir`, or "" when it reads.
std::string tile_set_error(const fs::path& dir) {
  try {
    read_tile_set(dir.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

struct Lie {
  const char* name;
  std::function<void(nlohmann::json&)> edit;
  const char* fragment;
};

TEST(HostileTileSets, EachLieInTilesJsonIsRefusedNamingIt) {
  tstest::TempDir t;
  const tstest::CliResult r =
      tstest::run_cli("tile --synthetic-size 65 --tile-size 16 --out " + (t / "good"));
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_EQ(tile_set_error(t.path / "good"), "");
  const nlohmann::json good = nlohmann::json::parse(std::ifstream(t.path / "good/tiles.json"));
  const std::vector<Lie> lies = {
      {"no_tiles",
       [](auto& j) {
         j["levels"][0]["tiles"] = {0, 0};
       },
       "level 0 lists 0 x 0"},
      {"negative_tiles",
       [](auto& j) {
         j["levels"][0]["tiles"] = {-1, -1};
       },
       "tiles[0] -1"},
      {"many_tiles",
       [](auto& j) {
         j["levels"][0]["tiles"] = {1000, 1000};
       },
       "level 0 lists 1000 x 1000"},
      {"zero_spacing",
       [](auto& j) {
         j["spacing_m"] = {0, 30};
       },
       "sample spacing 0 x 30"},
      {"negative_spacing",
       [](auto& j) {
         j["spacing_m"] = {-30, -30};
       },
       "sample spacing -30"},
      {"huge_spacing",
       [](auto& j) {
         j["spacing_m"] = {1e308, 1e308};
       },
       "sample spacing 1e+308"},
      {"huge_height", [](auto& j) { j["height_max"] = 1e308; }, "not finite heights"},
      {"inverted_heights", [](auto& j) { j["height_min"] = 5000; }, "heights 5000"},
      {"float_samples",
       [](auto& j) {
         j["samples"] = {1e308, 65};
       },
       "samples[0] must be"},
      {"wrapping_samples",
       [](auto& j) {
         j["samples"] = {4294967361LL, 65};
       },
       "samples[0]"},
      {"huge_bound", [](auto& j) { j["levels"][1]["tile_max_height"][0] = -1e30; },
       "tile_max_height of level 1 holds -1e+30"},
      {"level_count", [](auto& j) { j["bound_levels"] = 1e9; }, "bound_levels"},
  };
  for (const Lie& lie : lies) {
    const fs::path dir = t.path / lie.name;
    fs::create_directory(dir);
    for (const char* f : {"height.tif", "color.tif", "bound.tif"})
      fs::copy_file(t.path / "good" / f, dir / f);
    nlohmann::json j = good;
    lie.edit(j);
    std::ofstream(dir / "tiles.json") << j.dump();
    const std::string e = tile_set_error(dir);
    EXPECT_NE(e.find(lie.fragment), std::string::npos) << lie.name << ": " << e;
    EXPECT_NE(e.find("tiles.json"), std::string::npos) << lie.name << ": " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << lie.name << ": " << e;
  }
}

// A float GeoTIFF COG of 65 x 65 with pixel size `pixel` and `bad` at one sample.
std::string write_cog(const fs::path& path, double pixel, float bad) {
  GDALAllRegister();
  const int n = 65;
  GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", n, n, 1, GDT_Float32, nullptr);
  double gt[6] = {500000, pixel, 0, 4000000, 0, -pixel};
  GDALSetGeoTransform(mem, gt);
  std::vector<float> v(std::size_t(n) * n, 100.f);
  v[std::size_t(n) * 30 + 30] = bad;
  EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(mem, 1), GF_Write, 0, 0, n, n, v.data(), n, n,
                         GDT_Float32, 0, 0),
            CE_None);
  const char* opts[] = {"BLOCKSIZE=32", nullptr};
  GDALDatasetH out = GDALCreateCopy(GDALGetDriverByName("COG"), path.c_str(), mem, FALSE,
                                    const_cast<char**>(opts), nullptr, nullptr);
  EXPECT_NE(out, nullptr);
  if (out) GDALClose(out);
  GDALClose(mem);
  return path.string();
}

std::string cog_error(const std::string& cog) {
  try {
    open_cog(cog, "", 4, 1 << 20);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

TEST(HostileTileSets, CogsWithImpossibleSpacingOrHeightsAreRefused) {
  tstest::TempDir t;
  EXPECT_EQ(cog_error(write_cog(t.path / "ok.tif", 30, 120.f)), "");
  struct Case {
    const char* name;
    double pixel;
    float bad;
    const char* fragment;
  };
  for (const Case& c : {Case{"tiny.tif", 1e-300, 100.f, "sample spacing 1e-300"},
                        Case{"inf.tif", 30, INFINITY, "heights 100 .. inf"},
                        Case{"neginf.tif", 30, -INFINITY, "heights -inf"},
                        Case{"sentinel.tif", 30, -3e38f, "heights -3e+38"}}) {
    const std::string e = cog_error(write_cog(t.path / c.name, c.pixel, c.bad));
    EXPECT_NE(e.find(c.fragment), std::string::npos) << c.name << ": " << e;
    EXPECT_NE(e.find(c.name), std::string::npos) << e;
  }
}

// A UTM base of 401 x 401 at 30 m and a 1 m inset over its middle, written
// with or without a CRS, with or without an untagged -32768 block.
struct InsetFixture {
  Heightfield base;
  GridGeo grid;
  InsetFixture() {
    base.width = base.height = 41;
    base.spacing_x = base.spacing_y = 30;
    base.heights.assign(std::size_t(41) * 41, 100.f);
    GeoTransform geo;
    const double gt[6] = {500000, 30, 0, 4000000, 0, -30};
    std::copy(gt, gt + 6, geo.gt);
    geo.wkt = stream_test::utm_wkt(32611);
    base.geo = geo;
    base.name = "base";
    grid = grid_geo(base, 41, 41);
  }
  std::string write(const fs::path& path, bool with_crs, bool with_void) const {
    GDALAllRegister();
    const int n = 200;
    GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", n, n, 1, GDT_Int16, nullptr);
    double gt[6] = {500000 + 300, 1, 0, 4000000 - 300, 0, -1};
    GDALSetGeoTransform(mem, gt);
    if (with_crs) GDALSetProjection(mem, base.geo->wkt.c_str());
    std::vector<std::int16_t> v(std::size_t(n) * n, 150);
    if (with_void)
      for (int y = 50; y < 150; ++y)
        for (int x = 50; x < 150; ++x) v[std::size_t(y) * n + x] = -32768;
    EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(mem, 1), GF_Write, 0, 0, n, n, v.data(), n, n,
                           GDT_Int16, 0, 0),
              CE_None);
    GDALDatasetH out = GDALCreateCopy(GDALGetDriverByName("GTiff"), path.c_str(), mem, FALSE,
                                      nullptr, nullptr, nullptr);
    if (out) GDALClose(out);
    GDALClose(mem);
    return path.string();
  }
};

TEST(HostileTileSets, AnInsetWithoutACrsIsRefused) {
  tstest::TempDir t;
  InsetFixture f;
  Heightfield hf = f.base;
  const std::string path = f.write(t.path / "nocrs.tif", false, false);
  try {
    composite_insets(hf, f.grid, {InsetSpec{path, 0}});
    ADD_FAILURE() << "an inset without a CRS was composited";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nocrs.tif: an inset needs georeferencing with a CRS"),
              std::string::npos)
        << e.what();
  }
}

TEST(HostileTileSets, AnUntaggedSentinelBlockOfAnInsetIsAHoleNotADepth) {
  tstest::TempDir t;
  InsetFixture f;
  Heightfield hf = f.base;
  testing::internal::CaptureStderr();
  composite_insets(hf, f.grid, {InsetSpec{f.write(t.path / "void.tif", true, true), 0}});
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("a typical nodata sentinel"), std::string::npos) << err;
  float lowest = hf.heights[0];
  for (float h : hf.heights) lowest = std::min(lowest, h);
  EXPECT_GE(lowest, 100.f);  // the base (100 m) shows through the hole, never -32768
}

}  // namespace
}  // namespace terrasprite
