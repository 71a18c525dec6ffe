// SPDX-License-Identifier: MIT
// Geographic places on a terrain (GeoFrame) and the nodata fill choices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "geo_test_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/geo_frame.h"
#include "terrasprite/terrain/nodata_fill.h"
#include "terrasprite/terrain/resample.h"
#include "terrasprite/terrain/terrain.h"
#include "test_util.h"

using namespace terrasprite;

namespace {

Heightfield geographic_grid() {
  return tstest::geographic_grid(0.f, "grid");
}

}  // namespace

TEST(GeoFrame, SampleCentresMapToWorldMetres) {
  const Heightfield h = geographic_grid();
  const GeoFrame f(h, "test");
  const WorldXY c = f.world_of(138.55, 35.45, GeoMargin::kOnTerrain, "p");  // sample (5, 5)
  EXPECT_NEAR(c.x, 0, 1e-6);
  EXPECT_NEAR(c.y, 0, 1e-6);
  const WorldXY nw = f.world_of(138.05, 35.95, GeoMargin::kOnTerrain, "p");  // sample (0, 0)
  EXPECT_NEAR(nw.x, -5000, 1e-6);
  EXPECT_NEAR(nw.y, 5000, 1e-6);
  const auto [lon, lat] = f.lonlat_of({2000, -3000});  // sample (7, 8)
  EXPECT_NEAR(lon, 138.75, 1e-9);
  EXPECT_NEAR(lat, 35.15, 1e-9);
  // A resampled grid keeps its corners on the source's corner samples.
  const Heightfield r = resample_heightfield(h, 21, 21);
  const WorldXY rnw = GeoFrame(r, "test").world_of(138.05, 35.95, GeoMargin::kOnTerrain, "p");
  EXPECT_NEAR(rnw.x, -5000, 1e-6);
}

TEST(GeoFrame, RefusesBadPlacesAndTerrainsWithoutACrs) {
  const Heightfield h = geographic_grid();
  const GeoFrame f(h, "test");
  auto fails = [&](double lon, double lat, GeoMargin m, const char* fragment) {
    try {
      f.world_of(lon, lat, m, "--look-at");
      ADD_FAILURE() << lon << "," << lat;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  fails(138.5, 95, GeoMargin::kNearTerrain, "latitude");
  fails(NAN, 35, GeoMargin::kNearTerrain, "finite");
  fails(138.5, 37.0, GeoMargin::kOnTerrain, "not on the terrain");
  fails(141.0, 35.5, GeoMargin::kNearTerrain, "more than one extent");
  EXPECT_NO_THROW(f.world_of(139.3, 35.5, GeoMargin::kNearTerrain, "eye"));  // beyond, near
  Heightfield plain = h;
  plain.geo.reset();
  EXPECT_THROW(GeoFrame(plain, "--look-at"), InputError);
}

TEST(NodataFill, GdalFillsEveryVoidWithinTheRimsRange) {
  std::vector<float> z(64 * 64);
  std::vector<std::uint8_t> valid(z.size(), 1);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) z[std::size_t(j) * 64 + i] = float(100 + i);
  for (int j = 20; j < 30; ++j)
    for (int i = 20; i < 30; ++i) {
      z[std::size_t(j) * 64 + i] = 0;
      valid[std::size_t(j) * 64 + i] = 0;
    }
  EXPECT_EQ(fill_nodata_gdal(z, valid, 64, 64), 100);
  EXPECT_TRUE(std::all_of(valid.begin(), valid.end(), [](std::uint8_t v) { return v == 1; }));
  for (int i = 20; i < 30; ++i) {
    EXPECT_GE(z[25 * 64 + i], 119.f);
    EXPECT_LE(z[25 * 64 + i], 130.f);
  }
}

TEST(RealData, MtFujiSummitByLonLatAndItsVoids) {  // about 2 s: loads the 1201^2 tile twice
  const std::string d = tstest::shared_data();
  if (d.empty()) GTEST_SKIP() << "../shared/data is absent; real-data checks skipped";
  TerrainOptions o;
  o.dem = d + "/srtm3_mt_fuji/mt_fuji_90m.tif";
  o.dem_given = true;
  o.show_voids = true;
  const Terrain t = load_terrain(o);
  const Heightfield& h = t.heights;
  const WorldXY summit =
      GeoFrame(h, "test").world_of(138.7274, 35.3606, GeoMargin::kOnTerrain, "summit");
  EXPECT_GT(h.sample(summit.x, summit.y), 3600.f);  // Mt Fuji: 3742 m in this data
  EXPECT_EQ(h.nodata_count, 2437);
  EXPECT_EQ(std::count(h.voids.begin(), h.voids.end(), std::uint8_t{1}), 2437);
  EXPECT_EQ(h.fill_method, NodataFill::kAmle);
  long tinted = 0;  // texels of the derived texture that took the magenta tint
  for (int y = 0; y < t.texture.height; ++y)
    for (int x = 0; x < t.texture.width; ++x) {
      const std::uint8_t* p = t.texture.px(x, y);
      tinted += p[0] >= 128 && p[2] >= 128 && p[1] < 128;
    }
  EXPECT_GT(tinted, 2437);
  o.show_voids = false;
  o.fill = NodataFill::kGdal;
  const Terrain g = load_terrain(o);
  EXPECT_EQ(g.heights.fill_method, NodataFill::kGdal);
  EXPECT_EQ(g.heights.nodata_count, 2437);
}
