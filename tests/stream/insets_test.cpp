// SPDX-License-Identifier: MIT
// Insets: a 1 m inset (the base upsampled plus detail) over a 30 m base
// resampled to 1 m: inside it the inset's value, outside the base's, and a
// border blend without a step; another CRS is reprojected by GDAL; `tile
// --inset` records it in tiles.json.
#include "terrasprite/stream/insets.h"

#include <cpl_conv.h>
#include <gdal.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "stream_test_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/resample.h"
#include "test_util.h"

namespace terrasprite {
namespace {

using stream_test::utm_wkt;

constexpr double kX0 = 500000, kY0 = 4000000;  // the base's top-left corner (UTM 11N)

// A 21 x 21 base at 30 m (600 m square), georeferenced.
Heightfield base30() {
  Heightfield hf;
  hf.width = hf.height = 21;
  hf.spacing_x = hf.spacing_y = 30;
  hf.heights.resize(21 * 21);
  for (int j = 0; j < 21; ++j)
    for (int i = 0; i < 21; ++i) hf.at(i, j) = 100.f + 2.f * float(i) + 1.f * float(j);
  hf.geo = GeoTransform{{kX0, 30, 0, kY0, 0, -30}, utm_wkt(32611)};
  hf.name = "base";
  return hf;
}

float detail(int x, int y) {
  return 5.f + 1.5f * std::sin(float(x) * 0.1f) * std::cos(float(y) * 0.07f);
}

// A 1 m inset of 201 x 201 pixels whose pixel (0, 0) centre is grid sample
// (200, 200) of the base resampled to 1 m: the base plus detail, written to
// `path` in EPSG `epsg` (warped there by GDAL when it is not the base's).
std::string write_inset(const Heightfield& fine, const std::string& path, int epsg) {
  GDALAllRegister();
  const int n = 201;
  GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", n, n, 1, GDT_Float32, nullptr);
  const double x0 = kX0 + 15 + 200 - 0.5,
               y0 = kY0 - 15 - 200 + 0.5;  // base pixel centres are 15 m in
  double gt[6] = {x0, 1, 0, y0, 0, -1};
  GDALSetGeoTransform(mem, gt);
  const std::string wkt = utm_wkt(32611);
  GDALSetProjection(mem, wkt.c_str());
  std::vector<float> v(std::size_t(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      v[std::size_t(y) * n + x] = fine.at(200 + x, 200 + y) + detail(x, y);
  EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(mem, 1), GF_Write, 0, 0, n, n, v.data(), n, n,
                         GDT_Float32, 0, 0),
            CE_None);
  GDALDatasetH out = nullptr;
  if (epsg == 32611) {
    out = GDALCreateCopy(GDALGetDriverByName("GTiff"), path.c_str(), mem, FALSE, nullptr, nullptr,
                         nullptr);
  } else {
    const std::string t = "EPSG:" + std::to_string(epsg);
    const char* argv[] = {"-t_srs", t.c_str(), "-r", "bilinear", "-dstnodata", "nan", nullptr};
    GDALWarpAppOptions* o = GDALWarpAppOptionsNew(const_cast<char**>(argv), nullptr);
    out = GDALWarp(path.c_str(), nullptr, 1, &mem, o, nullptr);
    GDALWarpAppOptionsFree(o);
  }
  EXPECT_NE(out, nullptr);
  if (out) GDALClose(out);
  GDALClose(mem);
  return path;
}

TEST(Insets, InsideIsTheInsetOutsideTheBaseAndTheBorderBlendHasNoStep) {
  tstest::TempDir t;
  std::filesystem::create_directories(t.path);
  const Heightfield base = base30();
  const Heightfield fine0 = resample_heightfield(base, 601, 601);  // 1 m
  ASSERT_NEAR(fine0.spacing_x, 1.0, 1e-12);
  const std::string inset = write_inset(fine0, (t.path / "inset.tif").string(), 32611);
  const GridGeo g = grid_geo(fine0, 21, 21);
  EXPECT_NEAR(g.dx, 1.0, 1e-12);
  EXPECT_NEAR(g.x0, kX0 + 15, 1e-9);

  Heightfield fine = fine0, hard = fine0;
  const auto res = composite_insets(fine, g, {parse_inset(inset + ":blend=8")});
  composite_insets(hard, g, {parse_inset(inset + ":blend=0")});
  ASSERT_EQ(res.size(), 1u);
  EXPECT_GT(res[0].samples_full, 150 * 150);
  // Inside: the inset's own value (its pixel centres are grid samples).
  for (auto [x, y] : {std::pair{100, 100}, {20, 150}, {180, 30}})
    EXPECT_NEAR(fine.at(200 + x, 200 + y), fine0.at(200 + x, 200 + y) + detail(x, y), 1e-3)
        << x << "," << y;
  // Outside: the base's, untouched.
  for (auto [i, j] : {std::pair{50, 50}, {199, 300}, {300, 401}, {600, 600}})
    EXPECT_EQ(fine.at(i, j), fine0.at(i, j)) << i << "," << j;
  // Across the west border (column 200) along a row: the blend fades the
  // ~5 m offset in over 8 samples; a hard edge steps by it.
  auto max_step = [](const Heightfield& h, int j) {
    float m = 0;
    for (int i = 180; i < 230; ++i) m = std::max(m, std::abs(h.at(i + 1, j) - h.at(i, j)));
    return m;
  };
  const float base_step = max_step(fine0, 300);  // the base's own slope, ~0.067 m a sample
  EXPECT_LT(max_step(fine, 300), base_step + 6.5f / 8 + 0.2f);
  EXPECT_GT(max_step(hard, 300), 3.f);
  // The blend runs from the base's value at the edge to the inset's 8 samples in.
  EXPECT_EQ(fine.at(200, 300), fine0.at(200, 300));
  EXPECT_NEAR(fine.at(209, 300), fine0.at(209, 300) + detail(9, 100), 1e-3);
}

TEST(Insets, AnotherCrsIsReprojectedAndTileRecordsIt) {
  tstest::TempDir t;
  std::filesystem::create_directories(t.path);
  const Heightfield base = base30();
  Heightfield fine = resample_heightfield(base, 601, 601);
  const Heightfield fine0 = fine;
  // The same inset delivered in UTM zone 12 (warped there and back by GDAL).
  const std::string inset = write_inset(fine0, (t.path / "inset12.tif").string(), 32612);
  const auto res = composite_insets(fine, grid_geo(fine0, 21, 21), {parse_inset(inset)});
  EXPECT_GT(res[0].samples_full, 150 * 150);
  EXPECT_NEAR(fine.at(300, 300), fine0.at(300, 300) + detail(100, 100), 0.3);  // two bilinear warps
  EXPECT_EQ(fine.at(50, 50), fine0.at(50, 50));

  // The CLI: a georeferenced 30 m base resampled to 1 m with the inset over it.
  GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", 21, 21, 1, GDT_Float32, nullptr);
  GDALSetGeoTransform(mem, const_cast<double*>(base.geo->gt));
  GDALSetProjection(mem, base.geo->wkt.c_str());
  ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(mem, 1), GF_Write, 0, 0, 21, 21,
                         const_cast<float*>(base.heights.data()), 21, 21, GDT_Float32, 0, 0),
            CE_None);
  GDALClose(GDALCreateCopy(GDALGetDriverByName("GTiff"), (t.path / "base.tif").c_str(), mem, FALSE,
                           nullptr, nullptr, nullptr));
  GDALClose(mem);
  auto r =
      tstest::run_cli("tile --dem " + (t / "base.tif") + " --resample 601 --tile-size 64 --inset " +
                      inset + ":blend=6 --out " + (t / "tiles"));
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(t / "tiles/tiles.json"));
  ASSERT_EQ(j["insets"].size(), 1u);
  EXPECT_EQ(j["insets"][0]["blend_samples"], 6);
  EXPECT_GT(j["insets"][0]["samples_full"].get<long long>(), 150 * 150);
  EXPECT_NEAR(j["geotransform"][1].get<double>(), 1.0, 1e-9);  // kept through --resample
  EXPECT_EQ(j["insets"][0]["file"], inset);
  // Bad inset arguments: one line, exit 2, no output directory.
  for (const std::string& bad : {inset + ":blend=x", (t / "missing.tif"), std::string("")}) {
    r = tstest::run_cli("tile --dem " + (t / "base.tif") + " --inset '" + bad + "' --out " +
                        (t / "bad"));
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(t.path / "bad"));
  }
  r = tstest::run_cli("tile --synthetic-size 65 --inset " + inset + " --out " + (t / "bad"));
  EXPECT_EQ(r.status, 2) << r.output;
}

}  // namespace
}  // namespace terrasprite
